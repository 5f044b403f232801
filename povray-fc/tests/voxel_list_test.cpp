// Tests for the voxel-list block encoding: round trips, gap-size boundaries, sizes, early stop.
#include <algorithm>
#include <cstdint>
#include <memory>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "povrayfc/voxel_list.h"

using namespace povrayfc;

namespace {

std::vector<std::uint32_t> RoundTrip(const std::vector<std::uint32_t> &ids, std::size_t *blockSize = nullptr) {
    std::size_t size = VoxelListSize(ids);
    // Exact-size allocation so any read past the block is caught by sanitizers.
    std::unique_ptr<std::uint8_t[]> block(new std::uint8_t[size]);
    std::uint8_t *end = EncodeVoxelList(ids, block.get());
    EXPECT_EQ(std::size_t(end - block.get()), size);
    EXPECT_EQ(VoxelListBlockSize(block.get()), size);
    EXPECT_EQ(VoxelListCount(block.get()), ids.size());
    if (blockSize) *blockSize = size;
    std::vector<std::uint32_t> out;
    bool stopped = DecodeVoxelList(block.get(), [&](std::uint32_t v) {
        out.push_back(v);
        return false;
    });
    EXPECT_FALSE(stopped);
    return out;
}

}  // namespace

TEST(VoxelList, RoundTripsGapSizeBoundaries) {
    // Gaps (id - previous - 1): 0, 0, 255 (last 1-byte), 256 (first 2-byte), 65534 (last
    // 2-byte), 65535 (the escape marker value itself), 65536, plus the largest ids.
    std::vector<std::uint32_t> ids = {0, 1, 257, 514, 66049, 131585, 197122};
    ids.push_back(0x7ffffffeu);
    ids.push_back(0xfffffffeu);
    ids.push_back(0xffffffffu);
    // Every boundary gap decodes back to the same ids.
    EXPECT_EQ(RoundTrip(ids), ids);
    // A list that is just the maximum id works (first gap needs the escape).
    EXPECT_EQ(RoundTrip({0xffffffffu}), std::vector<std::uint32_t>{0xffffffffu});
    // A single id 0 works.
    EXPECT_EQ(RoundTrip({0}), std::vector<std::uint32_t>{0});
}

TEST(VoxelList, RoundTripsRandomListsOfAllLengths) {
    std::mt19937 rng(99);
    for (int len = 1; len <= 300; ++len) {
        std::vector<std::uint32_t> ids;
        // Mix of dense runs and far jumps, like rays through a grid.
        std::uint32_t v = rng() % 5000;
        for (int i = 0; i < len; ++i) {
            ids.push_back(v);
            int kind = int(rng() % 10);
            v += 1 + (kind < 5 ? 0 : kind < 8 ? rng() % 4096 : rng() % 200000);
        }
        // Any length (control bytes partly used or full) round-trips.
        ASSERT_EQ(RoundTrip(ids), ids) << len;
    }
}

TEST(VoxelList, DenseListsCostAboutOneByteAndAnEighthPerEntry) {
    std::vector<std::uint32_t> ids;
    for (std::uint32_t i = 0; i < 200; ++i) ids.push_back(4096 * 3 + 64 * (i / 8) + i % 8);
    std::size_t size = 0;
    EXPECT_EQ(RoundTrip(ids, &size), ids);
    // Gaps under 256 take 1 byte + 1 control bit; the header, pad and first id add a few.
    EXPECT_LE(size, 200 + 25 + 2 + 2 + 1 + 1u);
}

TEST(VoxelList, DecodeStopsWhenAsked) {
    std::vector<std::uint32_t> ids = {3, 9, 27, 81, 243};
    std::unique_ptr<std::uint8_t[]> block(new std::uint8_t[VoxelListSize(ids)]);
    EncodeVoxelList(ids, block.get());
    std::vector<std::uint32_t> seen;
    bool stopped = DecodeVoxelList(block.get(), [&](std::uint32_t v) {
        seen.push_back(v);
        return v == 27;
    });
    // The scan stops at the first id for which the callback returns true, and says so.
    EXPECT_TRUE(stopped);
    EXPECT_EQ(seen, (std::vector<std::uint32_t>{3, 9, 27}));
}
