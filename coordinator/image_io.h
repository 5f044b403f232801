// image_io.h - fc-master's image files, through OpenImageIO loaded as a plugin (fc-image.so
// beside fc-master; see image_plugin.cpp for why).
#pragma once

#include <cstdint>
#include <string>

namespace fc {

// Start loading the plugin on a background thread (call early; the calls below wait for it).
void preload_image_io();

// Write an 8-bit RGB Targa; false with err on failure (the plugin missing included).
bool write_targa(const std::string &path, int width, int height, const uint8_t *rgb,
                 std::string &err);

// Size and channels of an image file; false if it cannot be read as an image.
bool image_size(const std::string &path, int &width, int &height, int &channels);

} // namespace fc
