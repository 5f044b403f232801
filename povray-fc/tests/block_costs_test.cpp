// BlockCosts: a block's seconds go to the rectangles it meets, by its pixels in each.
#include "povrayfc/block_costs.h"

#include <gtest/gtest.h>

#include <thread>

namespace povrayfc {
namespace {

TEST(BlockCostsTest, ABlockInsideOneRectangleCountsWhollyThere) {
    const std::vector<BlockCost> blocks = {{0, 0, 39, 39, 1.0}, {40, 0, 79, 39, 2.0}, {80, 0, 119, 39, 4.0}};
    const std::vector<BlockCost> rects = {{0, 0, 79, 79}, {80, 0, 159, 79}};
    const std::vector<double> perRect = CostsPerRect(blocks, rects);
    ASSERT_EQ(perRect.size(), 2u);
    EXPECT_DOUBLE_EQ(perRect[0], 3.0);
    EXPECT_DOUBLE_EQ(perRect[1], 4.0);
}

TEST(BlockCostsTest, AStraddlingBlockIsSharedByItsPixelsInEachAndNothingOutsideIsLost) {
    // A 32-pixel block across the edge of two 80-pixel tiles (x 64..95: 16 pixels in
    // each), and rows 80..95 outside both rectangles.
    const std::vector<BlockCost> blocks = {{64, 64, 95, 95, 8.0}};
    const std::vector<BlockCost> rects = {{0, 0, 79, 79}, {80, 0, 159, 79}, {0, 200, 79, 279}};
    const std::vector<double> perRect = CostsPerRect(blocks, rects);
    EXPECT_DOUBLE_EQ(perRect[0], 4.0);
    EXPECT_DOUBLE_EQ(perRect[1], 4.0);
    EXPECT_DOUBLE_EQ(perRect[2], 0.0);
}

TEST(BlockCostsTest, ABlockMeetingNoRectangleCountsNowhere) {
    const std::vector<double> perRect = CostsPerRect({{200, 200, 231, 231, 5.0}}, {{0, 0, 79, 79}});
    EXPECT_DOUBLE_EQ(perRect[0], 0.0);
}

TEST(BlockCostsTest, ThreadsAddConcurrentlyAndAssignReplaces) {
    BlockCosts costs;
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t)
        threads.emplace_back([&costs, t] {
            for (int i = 0; i < 1000; ++i) costs.Add({t, i, t, i, 1.0});
        });
    for (std::thread &t : threads) t.join();
    EXPECT_EQ(costs.Snapshot().size(), 4000u);
    costs.Assign({{0, 0, 0, 0, 2.0}});
    ASSERT_EQ(costs.Snapshot().size(), 1u);
    costs.Clear();
    EXPECT_TRUE(costs.Snapshot().empty());
}

TEST(BlockCostsTest, ThreadCpuSecondsCountsThisThreadsWorkNotItsSleep) {
    const double start = ThreadCpuSeconds();
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    const double slept = ThreadCpuSeconds() - start;
    volatile double sink = 0;
    const double busyStart = ThreadCpuSeconds();
    while (ThreadCpuSeconds() - busyStart < 0.02) sink = sink + 1.0;
    EXPECT_LT(slept, 0.01);
    EXPECT_GE(ThreadCpuSeconds() - busyStart, 0.02);
}

}  // namespace
}  // namespace povrayfc
