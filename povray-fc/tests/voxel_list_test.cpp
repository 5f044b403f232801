// Tests for the voxel-list block encoding: round trips in recorded order, step-size
// boundaries, sizes, the one-pass NewVoxelList (also from several threads), early stop.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <memory>
#include <random>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "povrayfc/voxel_list.h"

using namespace povrayfc;

namespace {

std::vector<std::uint32_t> Decode(const std::uint8_t *block) {
    std::vector<std::uint32_t> out;
    bool stopped = DecodeVoxelList(block, [&](std::uint32_t v) {
        out.push_back(v);
        return false;
    });
    EXPECT_FALSE(stopped);
    return out;
}

std::vector<std::uint32_t> RoundTrip(const std::vector<std::uint32_t> &ids, std::size_t *blockSize = nullptr) {
    std::size_t size = VoxelListSize(ids);
    // Exact-size allocation so any read past the block is caught by sanitizers.
    std::unique_ptr<std::uint8_t[]> block(new std::uint8_t[size]);
    std::uint8_t *end = EncodeVoxelList(ids, block.get());
    EXPECT_EQ(std::size_t(end - block.get()), size);
    EXPECT_EQ(VoxelListBlockSize(block.get()), size);
    EXPECT_EQ(VoxelListCount(block.get()), ids.size());
    // The one-pass NewVoxelList writes the very same bytes.
    std::unique_ptr<std::uint8_t[]> fresh(NewVoxelList(ids.data(), ids.size()));
    EXPECT_EQ(VoxelListBlockSize(fresh.get()), size);
    EXPECT_EQ(std::memcmp(fresh.get(), block.get(), size), 0);
    if (blockSize) *blockSize = size;
    return Decode(block.get());
}

// Ids from steps: id_0 = steps[0], id_i = id_{i-1} + steps[i], modulo 2^32.
std::vector<std::uint32_t> FromSteps(std::initializer_list<std::int64_t> steps) {
    std::vector<std::uint32_t> ids;
    std::uint32_t v = 0;
    for (std::int64_t s : steps) ids.push_back(v += std::uint32_t(s));
    return ids;
}

// A list shaped like the voxels of a few rays through an nx*ny*nz grid, in walk order:
// steps of +-1, +-nx, +-nx*ny, a jump at each new ray.
std::vector<std::uint32_t> RayLikeList(std::mt19937 &rng, std::uint32_t nx, std::uint32_t ny, std::uint32_t nz,
                                       int rays) {
    std::vector<std::uint32_t> ids;
    for (int r = 0; r < rays; ++r) {
        std::int64_t x = rng() % nx, y = rng() % ny, z = rng() % nz;
        const int sx = rng() % 2 ? 1 : -1, sy = rng() % 2 ? 1 : -1, sz = rng() % 2 ? 1 : -1;
        for (int k = 0; k < 60; ++k) {
            ids.push_back(std::uint32_t(x + nx * (y + ny * z)));
            const int axis = int(rng() % 3);
            if (axis == 0) x += sx;
            if (axis == 1) y += sy;
            if (axis == 2) z += sz;
            if (x < 0 || y < 0 || z < 0 || x >= nx || y >= ny || z >= nz) break;
        }
    }
    return ids;
}

}  // namespace

TEST(VoxelList, RoundTripsStepSizeBoundaries) {
    // Steps (id - previous id, modulo 2^32) at every length boundary: 127 / -128 (last
    // 1-byte), 128 / -129 (first 2-byte), 32766 / -32768 (last 2-byte), 32767 / -32769
    // (first escaped), huge ones, and steps that wrap around 2^32.
    std::vector<std::uint32_t> ids = FromSteps(
        {1000000, 127, -128, 128, -129, 32766, -32768, 32767, -32769, 2000000000, -2000000000, 0, 1});
    for (std::uint32_t id : {0xffffffffu, 0u, 0x80000000u, 0u, 0x7fffffffu, 0xffffffffu}) ids.push_back(id);
    // Every boundary step decodes back to the same ids, in the same order.
    EXPECT_EQ(RoundTrip(ids), ids);
    // A list that is just the maximum id works (the first step is the id itself).
    EXPECT_EQ(RoundTrip({0xffffffffu}), std::vector<std::uint32_t>{0xffffffffu});
    // A single id 0 works.
    EXPECT_EQ(RoundTrip({0}), std::vector<std::uint32_t>{0});
}

TEST(VoxelList, EntryLengthsFollowTheStep) {
    std::size_t size = 0;
    // Steps in [-128, 127] take 1 byte: 8 entries = 1 control byte + 8 data bytes, plus the
    // 2-byte header and the pad.
    std::vector<std::uint32_t> ids = FromSteps({100, 127, -128, 1, 1, -64, -37, 1});
    EXPECT_EQ(RoundTrip(ids, &size), ids);
    EXPECT_EQ(size, 2 + 1 + 8 + 1u);
    // Steps of 128, -129, 32766 and -32768 take 2 bytes.
    ids = FromSteps({128, -129, 32766, -32768});
    EXPECT_EQ(RoundTrip(ids, &size), ids);
    EXPECT_EQ(size, 2 + 1 + 8 + 1u);
    // Steps of 32767 and -32769 take the escape: 6 bytes each.
    ids = FromSteps({32767, -32769});
    EXPECT_EQ(RoundTrip(ids, &size), ids);
    EXPECT_EQ(size, 2 + 1 + 12 + 1u);
}

TEST(VoxelList, RoundTripsRandomListsOfAllLengthsInAnyOrder) {
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
        // Any length (control bytes partly used or full) round-trips, ascending...
        ASSERT_EQ(RoundTrip(ids), ids) << len;
        // ... descending ...
        std::reverse(ids.begin(), ids.end());
        ASSERT_EQ(RoundTrip(ids), ids) << len;
        // ... and shuffled, order preserved.
        std::shuffle(ids.begin(), ids.end(), rng);
        ASSERT_EQ(RoundTrip(ids), ids) << len;
        // Arbitrary 32-bit ids, repeats included, too.
        for (std::uint32_t &id : ids) id = rng() % 3 ? std::uint32_t(rng()) : ids[0];
        ASSERT_EQ(RoundTrip(ids), ids) << len;
    }
}

TEST(VoxelList, RayOrderListsCostUnderTwoBytesPerEntry) {
    std::mt19937 rng(5);
    std::size_t entries = 0, bytes = 0;
    for (int pixel = 0; pixel < 200; ++pixel) {
        std::vector<std::uint32_t> ids = RayLikeList(rng, 64, 64, 64, 1 + pixel % 4);
        std::size_t size = 0;
        ASSERT_EQ(RoundTrip(ids, &size), ids);
        entries += ids.size();
        bytes += size;
    }
    // Walk-order steps (+-1, +-64: 1 byte; +-4096: 2 bytes) plus a control bit, the header,
    // the pad and an escape per ray stay under 2 bytes per entry.
    EXPECT_LT(double(bytes) / double(entries), 2.0) << double(bytes) / double(entries);
}

TEST(VoxelList, DenseListsCostAboutOneByteAndAnEighthPerEntry) {
    std::vector<std::uint32_t> ids;
    for (std::uint32_t i = 0; i < 200; ++i) ids.push_back(4096 * 3 + 64 * (i / 8) + i % 8);
    std::size_t size = 0;
    EXPECT_EQ(RoundTrip(ids, &size), ids);
    // Steps in [-128, 127] take 1 byte + 1 control bit; the header, pad and first id add a few.
    EXPECT_LE(size, 200 + 25 + 2 + 2 + 1 + 1u);
}

TEST(VoxelList, NewVoxelListFromSeveralThreads) {
    // Each thread encodes lists of growing and shrinking lengths (its scratch buffer grows)
    // and checks every block it made.
    std::vector<std::thread> pool;
    std::vector<int> failures(4, 0);
    for (int t = 0; t < 4; ++t)
        pool.emplace_back([t, &failures] {
            std::mt19937 rng(std::uint32_t(100 + t));
            for (int i = 0; i < 300; ++i) {
                std::vector<std::uint32_t> ids(1 + rng() % (i % 50 == 0 ? 20000 : 200));
                for (std::uint32_t &id : ids) id = rng() % 262144;
                std::unique_ptr<std::uint8_t[]> block(NewVoxelList(ids.data(), ids.size()));
                std::vector<std::uint32_t> out;
                DecodeVoxelList(block.get(), [&](std::uint32_t v) {
                    out.push_back(v);
                    return false;
                });
                if (out != ids || VoxelListBlockSize(block.get()) != VoxelListSize(ids)) ++failures[std::size_t(t)];
            }
        });
    for (std::thread &th : pool) th.join();
    // Every block from every thread decodes to its own list, at the predicted size.
    EXPECT_EQ(failures, std::vector<int>(4, 0));
}

TEST(VoxelList, DecodeStopsWhenAsked) {
    std::vector<std::uint32_t> ids = {243, 9, 27, 81, 3};
    std::unique_ptr<std::uint8_t[]> block(new std::uint8_t[VoxelListSize(ids)]);
    EncodeVoxelList(ids, block.get());
    std::vector<std::uint32_t> seen;
    bool stopped = DecodeVoxelList(block.get(), [&](std::uint32_t v) {
        seen.push_back(v);
        return v == 27;
    });
    // The scan stops at the first id for which the callback returns true, and says so.
    EXPECT_TRUE(stopped);
    EXPECT_EQ(seen, (std::vector<std::uint32_t>{243, 9, 27}));
}
