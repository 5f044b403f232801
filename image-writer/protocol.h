// protocol.h - the messages between fc-master (coordinator/master/image_writer_client.cpp)
// and fc-image-writer (fc_image_writer.cpp), on the helper's descriptors 3 (requests) and 4
// (replies), in native byte order (same machine). Plain C++: the helper is compiled with
// POV-Ray's flags, fc-master with ours.
#pragma once

#include <cstdint>

#include "frame-channel/frame_record.h"

namespace fc_image_writer {

const uint32_t kRequestMagic = 0x32574346;    // "FCW2"
const uint32_t kReplyMagic = 0x31524346;      // "FCR1"
const int kRequestFd = 3, kReplyFd = 4;       // as the helper sees them

enum Kind : int32_t {
    // Followed by width * height * 3 bytes: RGB as POV-Ray's Targa writer stores them, rows
    // top first. The reply is POV-Ray's Targa file of them, run-length encoded when rle,
    // recording file_gamma (<= 0: 1.0) as the renderer's file would.
    kEncodeTarga = 1,
    // Followed by width * height * 3 floats: the values the writer quantises (an rgbf frame
    // record's pixels), rows top first. The reply is width * height * 3 bytes, the frame
    // dithered by POV-Ray's own dither handler as diffusion says (frame_record.h).
    kDither = 2,
};

struct Request {
    uint32_t magic;
    int32_t kind;
    int32_t width, height;
    int32_t rle;                    // kEncodeTarga
    float file_gamma;               // kEncodeTarga
    fc::Diffusion diffusion;        // kDither
};

// Followed by size bytes: the answer when ok is 1, else the error message.
struct Reply {
    uint32_t magic;
    int32_t ok;
    uint64_t size;
};

} // namespace fc_image_writer
