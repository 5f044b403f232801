// cell_grid_test.cpp - a frame's cells: marked once, counted per frame and in all.
#include <gtest/gtest.h>

#include "cell_grid.h"

using namespace fc;

TEST(CellGrid, CountsCellsAndFramesOnce)
{
    CellGrid g(3, 4);
    EXPECT_FALSE(g.done(1, 2));
    EXPECT_TRUE(g.mark(1, 2));
    EXPECT_FALSE(g.mark(1, 2));     // the second result of a cell adds nothing
    EXPECT_TRUE(g.done(1, 2));
    EXPECT_EQ(g.cells_done(), 1);
    for (int t = 0; t < 4; t++)
        g.mark(1, t);
    EXPECT_TRUE(g.frame_done(1));
    EXPECT_FALSE(g.frame_done(0));
    EXPECT_EQ(g.frames_done(), 1);
    EXPECT_EQ(g.cells_done(), 4);
    g.mark_frame(0);
    g.mark_frame(0);
    g.mark_frame(2);
    EXPECT_TRUE(g.all_done());
    EXPECT_EQ(g.cells_done(), 12);
}
