// dither.cpp - POV-Ray's diffusion dithering over an assembled frame (see dither.h).
//
// The offset buffers and their quirks are POV-Ray's (base/image/encoding.cpp): Floyd-Steinberg
// reads a row's first offset before it swaps the row buffers, and 1D diffusion carries the
// error from the end of a row to the start of the next.
#include "dither.h"

#include <algorithm>
#include <cstring>

namespace fc {

namespace {

struct Offset {
    float c[3] = {0, 0, 0};
    void clear() { c[0] = c[1] = c[2] = 0; }
    void add(const Offset &e, float w)
    {
        for (int k = 0; k < 3; k++)
            c[k] += e.c[k] * w;
    }
};

float clip01(float x) { return x < 0.0f ? 0.0f : (x > 1.0f ? 1.0f : x); }

} // namespace

bool Quantizer::parse(const uint8_t *data, size_t size, std::string &err)
{
    const size_t want = 4 + 255 * 4 + 256 * 4;
    if (size != want) {
        err = "dithering quantizer of " + std::to_string(size) + " bytes, expected " +
              std::to_string(want);
        return false;
    }
    int32_t m;
    memcpy(&m, data, 4);
    memcpy(thresholds_, data + 4, sizeof thresholds_);
    memcpy(levels_, data + 4 + sizeof thresholds_, sizeof levels_);
    method_ = m;
    if (method_ != kDiffusion1D && method_ != kDiffusion2D && method_ != kFloydSteinberg) {
        err = "unknown diffusion dithering method " + std::to_string(method_);
        return false;
    }
    return true;
}

unsigned Quantizer::level(float x) const
{
    // Levels grow with x: the number of thresholds at or below x.
    return unsigned(std::upper_bound(thresholds_, thresholds_ + 255, x) - thresholds_);
}

float Quantizer::error(float x, unsigned level) const
{
    return clip01(x) - levels_[level];
}

void Quantizer::dither(const std::vector<float> &values, int width, int height,
                       std::vector<uint8_t> &rgb) const
{
    std::vector<Offset> a(size_t(width) + 2), b(size_t(width) + 2);
    Offset *this_row = a.data(), *next_row = b.data();
    Offset last;        // 1D diffusion
    for (int y = 0; y < height; y++) {
        for (int x = 0; x < width; x++) {
            size_t i = (size_t(y) * size_t(width) + size_t(x)) * 3;
            // getOffset
            Offset off;
            if (method_ == kDiffusion1D) {
                off = last;
                last.clear();
            } else if (method_ == kDiffusion2D) {
                off = this_row[x];
            } else {
                off = this_row[x + 1];
            }
            // quantize each channel; the offset becomes the error
            Offset err;
            for (int k = 0; k < 3; k++) {
                float v = values[i + size_t(k)] + off.c[k];
                unsigned q = level(v);
                rgb[i + size_t(k)] = uint8_t(q);
                err.c[k] = error(v, q);
            }
            // setError
            if (method_ == kDiffusion1D) {
                last = err;
                continue;
            }
            if (x == 0) {
                std::swap(this_row, next_row);
                for (int k = 0; k < width + 2; k++)
                    next_row[k].clear();
            }
            if (method_ == kDiffusion2D) {
                this_row[x + 1].add(err, 2 / 4.0f);
                next_row[x].add(err, 1 / 4.0f);
                next_row[x + 1].add(err, 1 / 4.0f);
            } else {
                this_row[x + 2].add(err, 7 / 16.0f);
                next_row[x].add(err, 3 / 16.0f);
                next_row[x + 1].add(err, 5 / 16.0f);
                next_row[x + 2].add(err, 1 / 16.0f);
            }
        }
    }
}

} // namespace fc
