// cost_model_test.cpp - what work costs, from the results: speeds, fresh starts and jumps
// priced in coherent frames, and what frame coherence saved.
#include <gtest/gtest.h>

#include "cost_model.h"

using namespace fc;

namespace {

ResultCost result(int slave, int index, double pixels, double trace, double rays, bool fresh)
{
    ResultCost r;
    r.slave = slave;
    r.index = index;
    r.pixels = pixels;
    r.trace = trace;
    r.rays = rays;
    r.fresh = fresh;
    return r;
}

} // namespace

TEST(CostModel, FreshFramesDoNotMeasureSpeedButPriceAFreshStart)
{
    CostModel c;
    c.set_frame_coherence(true);
    EXPECT_FALSE(c.cheap_moves());
    c.note_result(result(1, 0, 1000, 5.0, 5000, true));     // traced in full
    EXPECT_EQ(c.speed(1), 0);                                // no coherent speed yet
    c.note_result(result(1, 1, 1000, 1.0, 1000, false));
    EXPECT_DOUBLE_EQ(c.speed(1), 1000);
    EXPECT_DOUBLE_EQ(c.fresh_cost(), 5.0);                   // five coherent frames
    Savings s = c.savings();
    ASSERT_TRUE(s.known);
    EXPECT_DOUBLE_EQ(s.rays_spent, 6000);
    EXPECT_DOUBLE_EQ(s.rays_full, 10000);                    // 5 rays a pixel, 2000 pixels
}

TEST(CostModel, AForwardJumpIsPricedApart)
{
    CostModel c;
    c.set_frame_coherence(true);
    c.note_result(result(1, 0, 1000, 4.0, 0, true));
    c.note_result(result(1, 1, 1000, 1.0, 0, false));
    c.note_result(result(1, 7, 1000, 2.0, 0, false));        // jumped from 1 to 7
    EXPECT_DOUBLE_EQ(c.jump_cost(), 2.0);
    EXPECT_DOUBLE_EQ(c.speed(1), 1000);                      // the jump measured no speed
}

TEST(CostModel, WithoutFrameCoherenceEveryResultMeasures)
{
    CostModel c;
    c.set_frame_coherence(false);
    EXPECT_TRUE(c.cheap_moves());
    c.note_result(result(2, 0, 1000, 2.0, 100, true));
    EXPECT_DOUBLE_EQ(c.speed(2), 500);
    EXPECT_DOUBLE_EQ(c.job_seconds(), 2.0);
    c.note_result(result(2, 1, 1000, 1.0, 100, false));
    // Smoothed: the newest measurement weighs kSpeedWeight.
    EXPECT_DOUBLE_EQ(c.speed(2), 0.7 * 500 + 0.3 * 1000);
    EXPECT_FALSE(c.savings().known);
}
