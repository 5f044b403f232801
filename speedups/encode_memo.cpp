// EncodeMemo: the process-wide memo and its (re)initialisation.
#include "speedups/encode_memo.h"

#include <cstring>

namespace povrayfc {

namespace {
EncodeMemo &Memo() {
    static EncodeMemo memo;
    return memo;
}
}  // namespace

void EncodeMemo::SetEnabled(bool enabled) {
    EncodeMemo &m = Memo();
    m.enabled_ = enabled;
    m.owner_ = std::this_thread::get_id();
    if (!enabled) {
        m.image_ = nullptr;
        m.in_.Release();
        m.out_.Release();
        m.kept_.Release();
        m.spans_.Release();
        m.spanKept_.Release();
        m.spanPixel_.Release();
    }
}

EncodeMemo *EncodeMemo::For(const void *image, unsigned width, unsigned height, std::uint64_t settings) {
    EncodeMemo &m = Memo();
    if (!m.enabled_ || m.owner_ != std::this_thread::get_id()) return nullptr;
    if (m.image_ != image || m.width_ != width || m.height_ != height || m.settings_ != settings) {
        m.image_ = image;
        m.width_ = width;
        m.height_ = height;
        m.settings_ = settings;
        m.in_.Reset(std::size_t(width) * height * 4);
        m.out_.Reset(std::size_t(width) * height * 4);
        m.kept_.Reset(std::size_t(width) * height);
        m.spans_.Release();
        m.spanPixel_.Release();
        m.spanKept_.Reset(std::size_t(m.SpansPerRow()) * height);
    }
    return &m;
}

void EncodeMemo::Keep(unsigned x, unsigned y, const float in[4], const unsigned out[4]) {
    if (x >= width_ || y >= height_) return;
    const std::size_t i = std::size_t(y) * width_ + x;
    std::memcpy(&in_[i * 4], in, 4 * sizeof(float));
    kept_[i] = 1;
    for (int k = 0; k < 4; ++k) out_[i * 4 + k] = std::uint16_t(out[k]);
    // Its span's outputs may now be of other inputs than the span KeepSpan saw.
    spanKept_[std::size_t(y) * SpansPerRow() + x / kSpan] = 0;
    if (!spanPixel_.empty()) spanPixel_[i] = 0;
}

bool EncodeMemo::SpanUnchanged(unsigned x0, unsigned y, const float *rgbft) const {
    if (y >= height_ || x0 >= width_ || x0 % kSpan != 0 || !spanKept_[std::size_t(y) * SpansPerRow() + x0 / kSpan])
        return false;
    // Bits, not values, as Find compares.
    return std::memcmp(&spans_[(std::size_t(y) * width_ + x0) * 5], rgbft, SpanLength(x0) * 5 * sizeof(float)) == 0;
}

void EncodeMemo::KeepSpan(unsigned x0, unsigned y, const float *rgbft) {
    if (y >= height_ || x0 >= width_ || x0 % kSpan != 0) return;
    if (spans_.empty()) {
        spans_.Reset(std::size_t(width_) * height_ * 5);
        spanPixel_.Reset(std::size_t(width_) * height_);
    }
    const std::size_t first = std::size_t(y) * width_ + x0;
    std::memcpy(&spans_[first * 5], rgbft, SpanLength(x0) * 5 * sizeof(float));
    std::memset(&spanPixel_[first], 1, SpanLength(x0));
    spanKept_[std::size_t(y) * SpansPerRow() + x0 / kSpan] = 1;
}

}  // namespace povrayfc
