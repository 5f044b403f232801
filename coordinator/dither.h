// dither.h - POV-Ray's diffusion dithering (Dither=on, Dither_Method d1, d2, fs), run once
// over an assembled frame.
//
// Error diffusion carries each pixel's quantization error to its right and lower neighbours
// across the whole image, so a tile cannot be dithered on its own. With diffusion dithering
// the frame channel (patch 0022) sends each pixel's value as the Targa writer would quantize
// it (three floats) and, after the pixels, the quantizer of POV-Ray's gamma curve: the 255
// smallest values that quantize to 1..255 and the 256 decoded levels, computed by POV-Ray
// itself. The master then repeats Targa::Write's loop (encoding.cpp: getOffset, quantize,
// setError, pixel by pixel in raster order) with the same float arithmetic.
//
// Quantizer payload (little-endian): int32 method (kPOVList_DitherMethod_*: 1 = d1, 2 = d2,
// 3 = fs), 255 float thresholds, 256 float levels.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace fc {

class Quantizer {
public:
    static const int kDiffusion1D = 1, kDiffusion2D = 2, kFloydSteinberg = 3;

    // Read the quantizer payload; false with err when malformed.
    bool parse(const uint8_t *data, size_t size, std::string &err);

    // The 8-bit level of value x, and the linear error POV-Ray diffuses.
    unsigned level(float x) const;
    float error(float x, unsigned level) const;

    // Dither values (width * height * 3, raster order) into rgb.
    void dither(const std::vector<float> &values, int width, int height,
                std::vector<uint8_t> &rgb) const;

    int method() const { return method_; }

private:
    int method_ = 0;
    float thresholds_[255] = {};
    float levels_[256] = {};
};

} // namespace fc
