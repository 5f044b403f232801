// Tests for EncodeMemo: a pixel is found only with bit-identical inputs, for the image and
// settings it was kept for, and only while the memo is on, on the thread that turned it on.
#include <algorithm>
#include <cmath>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "speedups/encode_memo.h"

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

TEST(EncodeMemo, ASpanIsUnchangedOnlyWithItsBitsAndNoPixelKeptSince) {
    EncodeMemo::SetEnabled(true);
    int image = 0;
    const unsigned width = EncodeMemo::kSpan + 2;  // spans of kSpan and of 2 pixels
    EncodeMemo *m = EncodeMemo::For(&image, width, 3, 7);
    ASSERT_NE(m, nullptr);
    std::vector<float> row(std::size_t(width) * 5, 0.0f);
    for (unsigned x = 0; x < width; ++x) row[x * 5] = 0.01f * float(x);
    const unsigned x0 = EncodeMemo::kSpan;  // the short span at the end
    EXPECT_FALSE(m->SpanUnchanged(x0, 1, &row[x0 * 5]));  // never kept
    const unsigned out[4] = {186, 137, 0, 255};
    for (unsigned x = x0; x < width; ++x) {
        const float in[4] = {row[x * 5], 0.0f, 0.0f, 1.0f};
        m->Keep(x, 1, in, out);
    }
    m->KeepSpan(x0, 1, &row[x0 * 5]);
    ASSERT_TRUE(m->SpanUnchanged(x0, 1, &row[x0 * 5]));
    EXPECT_EQ(m->Outputs(x0 + 1, 1)[0], 186u);
    EXPECT_FALSE(m->SpanUnchanged(0, 1, &row[0]));        // the other span of the row
    EXPECT_FALSE(m->SpanUnchanged(x0, 0, &row[x0 * 5]));  // another row
    EXPECT_FALSE(m->SpanUnchanged(1, 1, &row[5]));        // not a span's start
    // Invariant: any other bit (here -0 for +0 in the last pixel's transmit) is a change.
    std::vector<float> other = row;
    other[width * 5 - 1] = -0.0f;
    EXPECT_FALSE(m->SpanUnchanged(x0, 1, &other[x0 * 5]));
    // A pixel kept since (another writer, another value) voids the span until kept again.
    const float changed[4] = {0.0f, 0.0f, 0.0f, 1.0f};
    const unsigned black[4] = {0, 0, 0, 255};
    m->Keep(x0 + 1, 1, changed, black);
    EXPECT_FALSE(m->SpanUnchanged(x0, 1, &row[x0 * 5]));
    m->KeepSpan(x0, 1, &row[x0 * 5]);
    EXPECT_TRUE(m->SpanUnchanged(x0, 1, &row[x0 * 5]));
    // Other settings reset the spans with the pixels.
    EXPECT_FALSE(EncodeMemo::For(&image, width, 3, 8)->SpanUnchanged(x0, 1, &row[x0 * 5]));
    EncodeMemo::SetEnabled(false);
}

TEST(EncodeMemo, APixelOfAChangedSpanIsUnchangedOnlyWithItsBitsAndNotKeptSince) {
    EncodeMemo::SetEnabled(true);
    int image = 0;
    const unsigned width = 2 * EncodeMemo::kSpan;
    EncodeMemo *m = EncodeMemo::For(&image, width, 2, 7);
    ASSERT_NE(m, nullptr);
    std::vector<float> row(std::size_t(width) * 5, 0.0f);
    for (unsigned x = 0; x < width; ++x) row[x * 5] = 0.01f * float(x);
    EXPECT_FALSE(m->PixelUnchanged(3, 1, &row[3 * 5]));  // no span kept yet
    const unsigned out[4] = {186, 137, 0, 255};
    for (unsigned x = 0; x < EncodeMemo::kSpan; ++x) {
        const float in[4] = {row[x * 5], 0.0f, 0.0f, 1.0f};
        m->Keep(x, 1, in, out);
    }
    m->KeepSpan(0, 1, &row[0]);
    EXPECT_TRUE(m->PixelUnchanged(3, 1, &row[3 * 5]));
    EXPECT_FALSE(m->PixelUnchanged(3, 0, &row[3 * 5]));                          // another row
    EXPECT_FALSE(m->PixelUnchanged(EncodeMemo::kSpan + 3, 1, &row[3 * 5]));      // a span never kept
    EXPECT_FALSE(m->PixelUnchanged(width, 1, &row[3 * 5]));                      // outside the image
    // One pixel of the span changes: the span is changed, its other pixels are not.
    std::vector<float> next = row;
    next[5 * 5 + 1] = 0.5f;
    EXPECT_FALSE(m->SpanUnchanged(0, 1, &next[0]));
    EXPECT_FALSE(m->PixelUnchanged(5, 1, &next[5 * 5]));
    EXPECT_TRUE(m->PixelUnchanged(4, 1, &next[4 * 5]));
    // Invariant: any other bit is a change (here -0 for +0 in the filter).
    next[6 * 5 + 3] = -0.0f;
    EXPECT_FALSE(m->PixelUnchanged(6, 1, &next[6 * 5]));
    // A pixel kept since holds the outputs of other inputs: not unchanged, even with the
    // span's bits, until the span is kept again; its neighbours stay unchanged.
    const float changed[4] = {0.5f, 0.5f, 0.0f, 1.0f};
    m->Keep(5, 1, changed, out);
    EXPECT_FALSE(m->PixelUnchanged(5, 1, &row[5 * 5]));
    EXPECT_TRUE(m->PixelUnchanged(4, 1, &row[4 * 5]));
    m->KeepSpan(0, 1, &next[0]);
    EXPECT_TRUE(m->PixelUnchanged(5, 1, &next[5 * 5]));
    EXPECT_FALSE(m->PixelUnchanged(5, 1, &row[5 * 5]));
    // Other settings reset the pixels with the spans.
    EXPECT_FALSE(EncodeMemo::For(&image, width, 2, 8)->PixelUnchanged(4, 1, &next[4 * 5]));
    EncodeMemo::SetEnabled(false);
}

TEST(EncodeMemo, RefreshSpanEncodesOnlyThePixelsThatChanged) {
    EncodeMemo::SetEnabled(true);
    int image = 0;
    const unsigned width = EncodeMemo::kSpan + 5;  // a full span and a short one
    EncodeMemo *m = EncodeMemo::For(&image, width, 1, 3);
    ASSERT_NE(m, nullptr);
    std::vector<float> row(std::size_t(width) * 5, 0.0f);
    for (unsigned x = 0; x < width; ++x) row[x * 5] = 0.01f * float(x);
    // An encoder that keeps its result, as GetEncodedRGBAValue does with the memo.
    std::vector<unsigned> encoded;
    auto encode = [&](const std::vector<float> &values) {
        return [&, values](unsigned x) {
            encoded.push_back(x);
            const float in[4] = {values[x * 5], 0.0f, 0.0f, 1.0f};
            const unsigned out[4] = {unsigned(values[x * 5] * 1000.0f), 0, 0, 255};
            m->Keep(x, 0, in, out);
        };
    };
    m->RefreshSpan(0, 0, &row[0], encode(row));
    m->RefreshSpan(EncodeMemo::kSpan, 0, &row[EncodeMemo::kSpan * 5], encode(row));
    EXPECT_EQ(encoded.size(), std::size_t(width));  // nothing kept yet: every pixel
    EXPECT_TRUE(m->SpanUnchanged(0, 0, &row[0]));
    EXPECT_TRUE(m->SpanUnchanged(EncodeMemo::kSpan, 0, &row[EncodeMemo::kSpan * 5]));
    // Again with the same bits: nothing is encoded.
    encoded.clear();
    m->RefreshSpan(0, 0, &row[0], encode(row));
    EXPECT_TRUE(encoded.empty());
    // Two pixels of the first span change: only they are encoded, and every output of the
    // span is then the one of its current values.
    std::vector<float> next = row;
    next[3 * 5] = 0.5f;
    next[7 * 5 + 4] = 0.25f;
    m->RefreshSpan(0, 0, &next[0], encode(next));
    EXPECT_EQ(encoded, (std::vector<unsigned>{3, 7}));
    EXPECT_EQ(m->Outputs(3, 0)[0], 500u);
    EXPECT_EQ(m->Outputs(4, 0)[0], unsigned(row[4 * 5] * 1000.0f));
    EXPECT_TRUE(m->SpanUnchanged(0, 0, &next[0]));
    EncodeMemo::SetEnabled(false);
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
