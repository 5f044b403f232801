// EncodeMemo: the encoded value of every pixel of the image the front end writes each
// frame, kept so that a pixel whose value did not change is not encoded again.
//
// POV-Ray encodes the whole image for every frame it writes (gamma curve with powf per
// channel, clipping, quantising); with frame coherence most pixels are reused unchanged
// and that encoding became about a fifth of a coherent frame's time. The memo keys each
// pixel by the exact bits of its input values: the same input under the same settings
// gives the same output, so the file is byte for byte what POV-Ray would write. Only for
// writes without dithering (a dithered pixel also depends on its neighbours' errors).
//
// Not thread-safe: the front end writes images from one thread; a call from another
// thread than the one that last enabled the memo bypasses it.
#ifndef SPEEDUPS_ENCODE_MEMO_H
#define SPEEDUPS_ENCODE_MEMO_H

#include <cstddef>
#include <cstdint>
#include <thread>

#include "speedups/zeroed_array.h"

namespace povrayfc {

class EncodeMemo {
  public:
    // The process-wide memo, or nullptr when it is off (fc off), used from another
    // thread, or the image is not the one it remembers (then it starts remembering
    // `image`, width x height, encoded with `settings`, a hash of everything else the
    // encoding depends on).
    static EncodeMemo *For(const void *image, unsigned width, unsigned height, std::uint64_t settings);
    // Turned on for the frames frame coherence renders (front end, before each write).
    static void SetEnabled(bool enabled);

    // The outputs remembered for pixel (x, y) when its inputs are bit for bit `in`.
    bool Find(unsigned x, unsigned y, const float in[4], unsigned out[4]) const {
        const std::size_t i = std::size_t(y) * width_ + x;
        if (x >= width_ || y >= height_ || !kept_[i] || !Same(&in_[i * 4], in)) return false;
        for (int k = 0; k < 4; ++k) out[k] = out_[i * 4 + k];
        return true;
    }
    void Keep(unsigned x, unsigned y, const float in[4], const unsigned out[4]);

    // Spans of kSpan pixels of a row (the last one shorter), for a writer that can read
    // the image's row as stored (5 floats per pixel: red, green, blue, filter, transmit):
    // with fc most of a frame is last frame's bit for bit, and one comparison of a span
    // spares a call, a conversion and a lookup per pixel. True when the span of row y at
    // x0 (a multiple of kSpan) was kept (KeepSpan, no Keep of its pixels since) with the
    // very bits at `rgbft` (its first pixel): every Outputs() of it is then what encoding
    // it gives.
    static constexpr unsigned kSpan = 32;
    bool SpanUnchanged(unsigned x0, unsigned y, const float *rgbft) const;
    // After every pixel of the span was found or kept for its current values.
    void KeepSpan(unsigned x0, unsigned y, const float *rgbft);
    // Inside a span that changed, pixel by pixel: true when (x, y) was in a span KeepSpan
    // saw, with the very bits at `rgbft` (its 5 floats), and was not kept (Keep) since: its
    // Outputs() are then what encoding it gives. A moving object changes a few pixels of
    // each span it crosses; the others need no encoding.
    bool PixelUnchanged(unsigned x, unsigned y, const float *rgbft) const {
        const std::size_t i = std::size_t(y) * width_ + x;
        if (x >= width_ || y >= height_ || spanPixel_.empty() || !spanPixel_[i]) return false;
        const std::uint32_t *p = reinterpret_cast<const std::uint32_t *>(&spans_[i * 5]);
        const std::uint32_t *q = reinterpret_cast<const std::uint32_t *>(rgbft);
        return ((p[0] ^ q[0]) | (p[1] ^ q[1]) | (p[2] ^ q[2]) | (p[3] ^ q[3]) | (p[4] ^ q[4])) == 0;
    }
    // Brings Outputs() up to date for the span of row y at x0 (a multiple of kSpan), whose
    // floats are at `rgbft` (5 a pixel), the one way every writer does it: nothing when the
    // span is unchanged; otherwise encodePixel(x) for each pixel that is not (it must encode
    // through the memo, which keeps the result, as GetEncodedRGBAValue does), then KeepSpan.
    template <typename EncodePixel>
    void RefreshSpan(unsigned x0, unsigned y, const float *rgbft, EncodePixel encodePixel) {
        if (x0 >= width_ || y >= height_ || SpanUnchanged(x0, y, rgbft)) return;
        const std::size_t n = SpanLength(x0);
        for (std::size_t k = 0; k < n; ++k)
            if (!PixelUnchanged(x0 + unsigned(k), y, rgbft + k * 5)) encodePixel(x0 + unsigned(k));
        KeepSpan(x0, y, rgbft);
    }
    // The outputs remembered for pixel (x, y): red, green, blue, alpha.
    const std::uint16_t *Outputs(unsigned x, unsigned y) const { return &out_[(std::size_t(y) * width_ + x) * 4]; }

  private:
    static bool Same(const float *a, const float *b) {
        // Bits, not values: -0 and +0, or two NaNs, need not encode alike.
        const std::uint32_t *p = reinterpret_cast<const std::uint32_t *>(a);
        const std::uint32_t *q = reinterpret_cast<const std::uint32_t *>(b);
        return ((p[0] ^ q[0]) | (p[1] ^ q[1]) | (p[2] ^ q[2]) | (p[3] ^ q[3])) == 0;
    }

    bool enabled_ = false;
    std::thread::id owner_;
    const void *image_ = nullptr;
    unsigned width_ = 0, height_ = 0;
    std::uint64_t settings_ = 0;
    // Per pixel of the whole image, but a renderer of a few tiles touches only their rows.
    ZeroedArray<float> in_;            // 4 per pixel
    ZeroedArray<std::uint8_t> kept_;   // per pixel: in_ and out_ hold a value
    ZeroedArray<std::uint16_t> out_;   // 4 per pixel (POV-Ray encodes to at most 16 bits)
    unsigned SpansPerRow() const { return (width_ + kSpan - 1) / kSpan; }
    std::size_t SpanLength(unsigned x0) const { return std::size_t(width_ - x0 < kSpan ? width_ - x0 : kSpan); }

    ZeroedArray<float> spans_;           // 5 per pixel, the spans KeepSpan saw (allocated on first use)
    ZeroedArray<std::uint8_t> spanKept_; // per span: spans_ and out_ hold it
    ZeroedArray<std::uint8_t> spanPixel_; // per pixel (with spans_): out_ encodes its spans_ bits
};

}  // namespace povrayfc

#endif
