// image_writer_protocol.h - the messages between fc-master (image_writer.cpp) and
// fc-image-writer (image_writer_main.cpp), on the helper's descriptors 3 (requests) and 4
// (replies), in native byte order (same machine). Plain C++: the helper is compiled with
// POV-Ray's flags, fc-master with ours.
#pragma once

#include <cstdint>

namespace fc_image_writer {

const uint32_t kRequestMagic = 0x31574346;    // "FCW1"
const uint32_t kReplyMagic = 0x31524346;      // "FCR1"
const int kRequestFd = 3, kReplyFd = 4;       // as the helper sees them

// Followed by width * height * 3 bytes: RGB as POV-Ray's Targa writer stores them, rows top
// first.
struct Request {
    uint32_t magic;
    int32_t width, height;
    int32_t rle;            // 1: run-length encoded Targa
    float file_gamma;       // what the file records (<= 0: 1.0)
};

// Followed by size bytes: the file when ok is 1, else the error message.
struct Reply {
    uint32_t magic;
    int32_t ok;
    uint64_t size;
};

} // namespace fc_image_writer
