// image_writer_client.h - fc-master's end of fc-image-writer: Targa frames encoded by POV-Ray's
// own writer, and frames dithered by POV-Ray's own error diffusion, in a helper process beside
// fc-master (image-writer/fc_image_writer.cpp says why: OpenImageIO's load costs the master's
// host 0.4 s of CPU, the helper 2 ms).
//
// The helper starts on first use and serves the whole run. Whatever goes wrong with it (not
// built, killed, a malformed reply) makes it unusable for the rest of the run with a reason:
// image_codec.cpp then encodes Targa with OpenImageIO instead (same pixels, so a frame is never
// lost), and a frame to dither by diffusion fails with that reason.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "frame-channel/frame_record.h"

namespace fc {

// Whether fc-image-writer sits beside fc-master (it may still fail to start).
bool image_writer_present();

// Encode width x height RGB bytes (rows top first), stored values as POV-Ray's Targa writer
// stores them, as POV-Ray's Targa file, run-length encoded when rle, recording file_gamma
// (<= 0: 1.0) as that writer would, into out. False with err, after which the helper is not
// used again.
bool writer_encode_targa(int width, int height, bool rle, double file_gamma, const uint8_t *rgb,
                         std::vector<uint8_t> &out, std::string &err);

// Dither width x height pixels of values (3 floats a pixel, rows top first: an rgbf frame
// record's pixels) into rgb (3 bytes a pixel) with POV-Ray's own dither handler, as diffusion
// says. False with err, after which the helper is not used again: diffusion dithering has no
// other implementation.
bool writer_dither(int width, int height, const Diffusion &diffusion, const float *values,
                   std::vector<uint8_t> &rgb, std::string &err);

// Close the helper's requests and reap it (it ends at the end of its input).
void stop_image_writer();

} // namespace fc
