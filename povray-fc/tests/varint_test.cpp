// Tests for the LEB128 varint helpers used in voxel-list headers.
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "povrayfc/varint.h"

using namespace povrayfc;

TEST(Varint, RoundTripsBoundaryValues) {
    const std::uint32_t values[] = {0, 1, 127, 128, 255, 16383, 16384, 2097151, 2097152, 268435455, 268435456,
                                    0xfffffffeu, 0xffffffffu};
    for (std::uint32_t v : values) {
        std::uint8_t buf[kMaxVarintBytes + 1] = {};
        std::uint8_t *end = PutVarint(buf, v);
        // The encoded length matches VarintSize and never exceeds kMaxVarintBytes.
        EXPECT_EQ(end - buf, VarintSize(v)) << v;
        EXPECT_LE(end - buf, kMaxVarintBytes);
        std::uint32_t back = 0;
        const std::uint8_t *after = GetVarint(buf, back);
        // Decoding gives back the value and consumes exactly the encoded bytes.
        EXPECT_EQ(back, v);
        EXPECT_EQ(after, end);
    }
    // Values below 128 take one byte; 128 needs two (7 bits per byte).
    EXPECT_EQ(VarintSize(127), 1);
    EXPECT_EQ(VarintSize(128), 2);
    EXPECT_EQ(VarintSize(0xffffffffu), 5);
}

TEST(Varint, ConsecutiveValuesDecodeInOrder) {
    std::vector<std::uint8_t> buf(64);
    std::uint8_t *p = buf.data();
    for (std::uint32_t v : {300u, 5u, 70000u}) p = PutVarint(p, v);
    const std::uint8_t *q = buf.data();
    std::uint32_t a, b, c;
    q = GetVarint(GetVarint(GetVarint(q, a), b), c);
    // A stream of varints decodes back in order without separators.
    EXPECT_EQ(a, 300u);
    EXPECT_EQ(b, 5u);
    EXPECT_EQ(c, 70000u);
    EXPECT_EQ(q, p);
}
