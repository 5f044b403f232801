// render_blocks_test.cpp - unit tests of the slaves' render block size.
#include <gtest/gtest.h>

#include "render_blocks.h"

using namespace fc;

// The slaves' block size: inside the tiles wherever no pixel depends on the block grid.
TEST(RenderBlocks, RenderBlocksInsideTiles)
{
    ResolvedOptions no_aa;                       // Create_Ini leaves defaults out
    EXPECT_TRUE(slave_render_block(no_aa, 80) == 40);  // the paper's tiles: 2 blocks a side
    EXPECT_TRUE(slave_render_block(no_aa, 64) == 0);   // 32 divides it already
    EXPECT_TRUE(slave_render_block(no_aa, 37) == 37);  // the tile itself: one block
    EXPECT_TRUE(slave_render_block(no_aa, 200) == 50);
    EXPECT_TRUE(slave_render_block(no_aa, 97) == 0);   // a prime above 64: keep the default
    ResolvedOptions own = {{"Render_Block_Size", "16"}};
    EXPECT_TRUE(slave_render_block(own, 80) == 0);     // the user's 16 divides 80
    EXPECT_TRUE(slave_render_block(own, 72) == 36);
    ResolvedOptions m2 = {{"Antialias", "On"}, {"Sampling_Method", "2"}};
    EXPECT_TRUE(!pixels_depend_on_block_grid(m2) && slave_render_block(m2, 80) == 40);
    ResolvedOptions m1 = {{"Antialias", "On"}, {"Antialias_Threshold", "0.3"}};
    EXPECT_TRUE(pixels_depend_on_block_grid(m1) && slave_render_block(m1, 80) == 0);
    ResolvedOptions off = {{"Antialias", "Off"}, {"Sampling_Method", "1"}};
    EXPECT_TRUE(!pixels_depend_on_block_grid(off) && slave_render_block(off, 80) == 40);
}
