// Tests for ZeroedArray: zeros on every Reset, and pages made only where written.
#include <sys/resource.h>

#include <cstdint>

#include <gtest/gtest.h>

#include "speedups/encode_memo.h"
#include "speedups/zeroed_array.h"

using namespace povrayfc;

namespace {

long PeakKilobytes() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return usage.ru_maxrss;
}

TEST(ZeroedArray, EveryResetGivesZeros) {
    ZeroedArray<std::uint16_t> a;
    EXPECT_TRUE(a.empty());
    a.Reset(1000);
    ASSERT_EQ(a.size(), 1000u);
    for (std::size_t i = 0; i < a.size(); ++i) ASSERT_EQ(a[i], 0) << i;
    a[7] = 42;
    EXPECT_EQ(a[7], 42);
    // Invariant: a Reset starts again from zeros, whatever was written before.
    a.Reset(1000);
    EXPECT_EQ(a[7], 0);
    a.Release();
    EXPECT_TRUE(a.empty());
    EXPECT_EQ(a.size(), 0u);
}

TEST(ZeroedArray, OnlyWrittenPagesCostMemory) {
    const long before = PeakKilobytes();
    ZeroedArray<float> a;
    a.Reset(std::size_t(64) << 20);  // 256 MB of zeros
    a[0] = 1.0f;
    a[a.size() / 2] = 2.0f;
    EXPECT_EQ(a[1], 0.0f);
    EXPECT_EQ(a[a.size() - 1], 0.0f);
    // Invariant: the peak resident size grew by the pages touched, not by 256 MB.
    EXPECT_LT(PeakKilobytes() - before, 32 * 1024);
}

// A renderer of frame division remembers the encoding of the pixels of its tiles only: the
// memo of a 3840x2160 frame (46 bytes a pixel when all of it is used) costs the rows it
// keeps.
TEST(ZeroedArray, EncodeMemoOfALargeFrameCostsTheRowsItKeeps) {
    const long before = PeakKilobytes();
    EncodeMemo::SetEnabled(true);
    int image = 0;
    EncodeMemo *m = EncodeMemo::For(&image, 3840, 2160, 1);
    ASSERT_NE(m, nullptr);
    float rgbft[EncodeMemo::kSpan * 5] = {0.25f};
    const float in[4] = {0.25f, 0.0f, 0.0f, 0.0f};
    const unsigned out[4] = {137, 0, 0, 255};
    for (unsigned y = 100; y < 180; ++y)
        for (unsigned x0 = 160; x0 < 240; x0 += EncodeMemo::kSpan) {
            for (unsigned x = x0; x < x0 + EncodeMemo::kSpan; ++x) m->Keep(x, y, in, out);
            m->KeepSpan(x0, y, rgbft);
        }
    EXPECT_TRUE(m->SpanUnchanged(160, 120, rgbft));
    EXPECT_FALSE(m->SpanUnchanged(160, 1000, rgbft));
    EXPECT_LT(PeakKilobytes() - before, 64 * 1024);
    EncodeMemo::SetEnabled(false);
}

}  // namespace
