// liveness_test.cpp - deadlines learned from the run.
#include <gtest/gtest.h>

#include "liveness.h"

using namespace fc;

TEST(Liveness, BeforeAnyJobTheFallbackHolds)
{
    Liveness l(120);
    EXPECT_DOUBLE_EQ(l.deadline(1, 100, 1000, false, 1), 120);
    Liveness short_timeout(3);
    EXPECT_DOUBLE_EQ(short_timeout.deadline(1, 100, 1000, false, 1), Liveness::kFloor);
}

TEST(Liveness, AMultipleOfTheHostsMedianWithAFloor)
{
    const double k = Liveness::kFactor;
    Liveness l(120);
    // Host 100's jobs: 4 s for 1000 pixels, and one slow outlier the median ignores.
    for (double s : {4.0, 4.0, 4.0, 30.0})
        l.job_took(1, 100, 1000, s);
    EXPECT_DOUBLE_EQ(l.deadline(1, 100, 1000, false, 1), k * 4);
    // Twice the pixels, twice the deadline.
    EXPECT_DOUBLE_EQ(l.deadline(1, 100, 2000, false, 1), k * 8);
    // A copy, or a slave's first job, starts its renderer afresh: the fresh cost on top.
    EXPECT_DOUBLE_EQ(l.deadline(1, 100, 1000, true, 3), k * 12);
    EXPECT_DOUBLE_EQ(l.deadline(2, 100, 1000, false, 3), k * 12);
    // A host without jobs of its own goes by every host's.
    EXPECT_DOUBLE_EQ(l.deadline(1, 200, 1000, false, 1), k * 4);
    // Fast jobs never give less than the floor.
    Liveness fast(120);
    fast.job_took(1, 100, 1000, 0.1);
    EXPECT_DOUBLE_EQ(fast.deadline(1, 100, 1000, false, 1), Liveness::kFloor);
}

TEST(Liveness, TheMedianOfAnEvenCountIsTheMeanOfItsMiddleTwo)
{
    // A run's first two jobs: the second took twice the first (the renderer warming up).
    Liveness l(120);
    l.job_took(1, 100, 1000, 4.0);
    l.job_took(1, 100, 1000, 8.0);
    EXPECT_DOUBLE_EQ(l.seconds_per_pixel(100), 0.006);
    EXPECT_DOUBLE_EQ(l.deadline(1, 100, 1000, false, 1), Liveness::kFactor * 6);
}

TEST(Liveness, ASecondAttemptHangsOnlyAfterTwentyTimesTheMedianAndAMinute)
{
    Liveness before_any(120);
    EXPECT_DOUBLE_EQ(before_any.hang_deadline(100, 1000), 120);
    Liveness l(120);
    for (double s : {4.0, 4.0, 4.0})
        l.job_took(1, 100, 1000, s);
    EXPECT_DOUBLE_EQ(l.hang_deadline(100, 1000), 80);
    EXPECT_GT(l.hang_deadline(100, 1000), l.deadline(1, 100, 1000, true, 3));
    Liveness fast(120);
    fast.job_took(1, 100, 1000, 0.1);
    EXPECT_DOUBLE_EQ(fast.hang_deadline(100, 1000), Liveness::kHangFloor);
}
