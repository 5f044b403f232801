// image_codec.h - fc-master's image encoding and decoding through OpenImageIO, loaded as a
// plugin (fc-image.so beside fc-master; see image_plugin/ for why) in the background.
//
// Images are 3-channel, rows top first, with samples of one PixelType. Encoding goes into
// memory: the caller writes the bytes itself (write_file_durably, durable_write.h), so that a
// full disk is reported as such and never leaves a short file under a frame's name.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace fc {

// Sample types of stored pixels (the numbers are the plugin's).
enum class PixelType { U8 = 0, U16 = 1, Half = 2 };

size_t pixel_type_bytes(PixelType t);

// Start loading the plugin on a background thread (call early; the calls below wait for it).
void preload_image_io();

// Whether that background load still runs: a call below would wait for it.
bool image_io_loading();

// Whether the plugin was loaded (or failed to load): a call below would not wait.
bool image_io_ready();

// Wait for the background load to end. Call before the process exits: exit handlers that
// run while the load is under way abort in OpenImageIO's own destructors (an assertion in
// unordered_map_concurrent.h, seen when a render failed at once).
void wait_image_io();

// Encode width x height pixels with OpenImageIO in a format ("targa", "png", "openexr") with
// compression ("" = default, "fast" = the quickest encoding, "rle" for Targa) into out. False
// with err (the plugin missing included). Which frames go to fc-image-writer instead is
// frame_encoder.h's choice.
bool encode_with_image_io(const std::string &format, const std::string &compression, int width,
                          int height, PixelType type, const void *pixels,
                          std::vector<uint8_t> &out, std::string &err);

// Read a whole image file as 3 channels of type into pixels (a short or damaged file is an
// error); channels is the file's own count. False with err.
bool read_image(const std::string &path, PixelType type, int &width, int &height, int &channels,
                std::vector<uint8_t> &pixels, std::string &err);

// Half-float conversions, rounded as OpenEXR rounds (the plugin must be loadable).
bool floats_to_half(const float *in, uint16_t *out, size_t n, std::string &err);
bool half_to_floats(const uint16_t *in, float *out, size_t n, std::string &err);

} // namespace fc
