// Tests for RecordingPolicy: when recording pauses and when it resumes.
#include <gtest/gtest.h>

#include "povrayfc/recording_policy.h"

namespace povrayfc {
namespace {

TEST(RecordingPolicy, AFullFramePausesUntilALocalChange) {
    RecordingPolicy p;
    p.AfterRecordedFrame(true, 0);
    ASSERT_TRUE(p.Paused());
    EXPECT_FALSE(p.ResumeWith(false));  // the camera still moves
    EXPECT_TRUE(p.ResumeWith(true));    // it stopped: record again at once
    EXPECT_FALSE(p.Paused());
}

TEST(RecordingPolicy, CoherentFramesThatPayResetTheBusyStreak) {
    RecordingPolicy p;
    p.AfterRecordedFrame(false, 0.95);
    p.AfterRecordedFrame(false, 0.05);
    p.AfterRecordedFrame(false, 0.95);
    EXPECT_FALSE(p.Paused());
    p.AfterRecordedFrame(false, 0.95);
    EXPECT_TRUE(p.Paused());
}

TEST(RecordingPolicy, BusyFramesBackOffLongerEachTime) {
    RecordingPolicy p;
    int waited[3];
    for (int round = 0; round < 3; ++round) {
        p.AfterRecordedFrame(false, 0.95);
        p.AfterRecordedFrame(false, 0.97);
        ASSERT_TRUE(p.Paused());
        waited[round] = 0;
        while (!p.ResumeWith(true)) ++waited[round];
    }
    // Invariant: each fruitless try doubles the pause (2, 4, 8 frames).
    EXPECT_EQ(waited[0], 2);
    EXPECT_EQ(waited[1], 4);
    EXPECT_EQ(waited[2], 8);
    // A frame that pays resets the back-off.
    p.AfterRecordedFrame(false, 0.1);
    p.AfterRecordedFrame(false, 0.95);
    p.AfterRecordedFrame(false, 0.95);
    int wait = 0;
    while (!p.ResumeWith(true)) ++wait;
    EXPECT_EQ(wait, 2);
}

TEST(RecordingPolicy, WorkShareWeighsRaysOnlyWhenManySamplesAreTraced) {
    // Few samples traced: the rays are not looked at.
    EXPECT_EQ(RecordingPolicy::WorkShare(0.2, 5000.0, 1000.0), 0.2);
    // Many traced, and they were the ones with many rays: the rays say busy.
    EXPECT_EQ(RecordingPolicy::WorkShare(0.63, 950.0, 1000.0), 0.95);
    EXPECT_GT(RecordingPolicy::WorkShare(0.63, 950.0, 1000.0), RecordingPolicy::kBusyShare);
    // The rays never make a frame look less busy than its samples, nor count unmeasured.
    EXPECT_EQ(RecordingPolicy::WorkShare(0.7, 300.0, 1000.0), 0.7);
    EXPECT_EQ(RecordingPolicy::WorkShare(0.7, 300.0, 0.0), 0.7);
}

}  // namespace
}  // namespace povrayfc
