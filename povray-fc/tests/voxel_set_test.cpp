// Tests for VoxelSet (bitset over voxel ids) and DirtyMask (per-pixel flags).
#include <stdexcept>

#include <gtest/gtest.h>

#include "povrayfc/dirty_mask.h"
#include "povrayfc/voxel_set.h"

using namespace povrayfc;

TEST(VoxelSet, SetTestCountAcrossWordBoundaries) {
    VoxelSet s(130);
    // A new set is empty.
    EXPECT_EQ(s.Count(), 0u);
    EXPECT_FALSE(s.Any());
    for (std::uint32_t v : {0u, 63u, 64u, 127u, 129u, 64u}) s.Set(v);
    // Set bits are found, unset ones are not; setting twice counts once.
    EXPECT_TRUE(s.Test(63));
    EXPECT_TRUE(s.Test(64));
    EXPECT_TRUE(s.Test(129));
    EXPECT_FALSE(s.Test(65));
    EXPECT_FALSE(s.Test(128));
    EXPECT_EQ(s.Count(), 5u);
    EXPECT_TRUE(s.Any());
    // Ids past the end are reported absent rather than read out of bounds.
    EXPECT_FALSE(s.Test(130));
    EXPECT_FALSE(s.Test(100000));
    // Setting an id past the end is rejected.
    EXPECT_THROW(s.Set(130), std::invalid_argument);
    s.SetAll();
    // SetAll sets exactly Size() bits (no stray bits past the end).
    EXPECT_EQ(s.Count(), 130u);
    s.Reset();
    EXPECT_EQ(s.Count(), 0u);
}

TEST(DirtyMask, SetTestCountAll) {
    DirtyMask m(5, 3);
    // A new mask is clean.
    EXPECT_EQ(m.Count(), 0u);
    m.Set(4, 2);
    m.Set(0, 0);
    m.Set(0, 0);
    // Set marks exactly that pixel (row-major, no aliasing between rows).
    EXPECT_TRUE(m.Test(4, 2));
    EXPECT_FALSE(m.Test(4, 1));
    EXPECT_FALSE(m.Test(0, 1));
    EXPECT_EQ(m.Count(), 2u);
    m.Set(4, 2, false);
    // Set(x, y, false) clears a pixel.
    EXPECT_FALSE(m.Test(4, 2));
    m.SetAll();
    EXPECT_EQ(m.Count(), 15u);
    // Non-positive sizes are rejected.
    EXPECT_THROW(DirtyMask(0, 3), std::invalid_argument);
    EXPECT_THROW(DirtyMask(3, -1), std::invalid_argument);
}
