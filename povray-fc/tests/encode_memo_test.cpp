// Tests for EncodeMemo: a pixel is found only with bit-identical inputs, for the image and
// settings it was kept for, and only while the memo is on, on the thread that turned it on.
#include <cmath>
#include <thread>

#include <gtest/gtest.h>

#include "povrayfc/encode_memo.h"

using namespace povrayfc;

namespace {

TEST(EncodeMemo, FindsOnlyWhatWasKeptForTheSameInputBits) {
    EncodeMemo::SetEnabled(true);
    int image = 0;
    EncodeMemo *m = EncodeMemo::For(&image, 4, 3, 7);
    ASSERT_NE(m, nullptr);
    const float in[4] = {0.5f, 0.25f, 0.0f, 1.0f};
    unsigned out[4];
    EXPECT_FALSE(m->Find(1, 2, in, out));  // nothing kept yet
    const unsigned encoded[4] = {186, 137, 0, 255};
    m->Keep(1, 2, in, encoded);
    ASSERT_TRUE(m->Find(1, 2, in, out));
    EXPECT_EQ(out[0], 186u);
    EXPECT_EQ(out[3], 255u);
    // Invariant: other bits (here -0 for +0) or another pixel are a miss.
    const float negativeZero[4] = {0.5f, 0.25f, -0.0f, 1.0f};
    EXPECT_FALSE(m->Find(1, 2, negativeZero, out));
    EXPECT_FALSE(m->Find(2, 2, in, out));
    EXPECT_FALSE(m->Find(9, 9, in, out));  // outside the image
    // The same image and settings keep the memo; other settings or another image reset it.
    EXPECT_TRUE(EncodeMemo::For(&image, 4, 3, 7)->Find(1, 2, in, out));
    EXPECT_FALSE(EncodeMemo::For(&image, 4, 3, 8)->Find(1, 2, in, out));
    EncodeMemo::For(&image, 4, 3, 7)->Keep(1, 2, in, encoded);
    int other = 0;
    EXPECT_FALSE(EncodeMemo::For(&other, 4, 3, 7)->Find(1, 2, in, out));
}

TEST(EncodeMemo, OffOrAnotherThreadMeansNoMemo) {
    int image = 0;
    EncodeMemo::SetEnabled(false);
    EXPECT_EQ(EncodeMemo::For(&image, 4, 3, 7), nullptr);
    EncodeMemo::SetEnabled(true);
    EncodeMemo *fromOther = reinterpret_cast<EncodeMemo *>(1);
    std::thread t([&] { fromOther = EncodeMemo::For(&image, 4, 3, 7); });
    t.join();
    EXPECT_EQ(fromOther, nullptr);
    EncodeMemo::SetEnabled(false);
}

}  // namespace
