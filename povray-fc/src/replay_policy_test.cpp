#include "povrayfc/replay_policy.h"

#include <vector>

#include <gtest/gtest.h>

namespace povrayfc {
namespace {

// How many of `frames` frames keep replays when every frame runs `runs` searches and tests
// again and keeps samples of `kept` segments (a frame that keeps none runs none the next).
int FramesKeeping(int frames, std::uint64_t runs, std::uint64_t kept) {
    ReplayPolicy policy;
    int keeping = 0;
    for (int f = 0; f < frames; ++f) {
        const bool keep = policy.Keep();
        keeping += keep;
        policy.AfterFrame(keep ? runs : 0, keep ? kept : 0);
    }
    return keeping;
}

TEST(ReplayPolicy, KeepsWhileTheRaysKeptPayForTheRuns) {
    EXPECT_EQ(FramesKeeping(100, 1000, 4000), 100);
    EXPECT_EQ(FramesKeeping(100, 1000, 9000), 100);
    // Frames with nothing to run say nothing.
    EXPECT_EQ(FramesKeeping(100, 0, 0), 100);
    // Samples a run keeps that are hardly more than the run (a camera ray and a shadow test).
    EXPECT_LT(FramesKeeping(100, 1000, 3999), 10);
}

TEST(ReplayPolicy, PausesLongerEachTimeTriesDoNotPay) {
    // Kept 1 in 1000: keep, pause 16; keep, pause 32; keep, pause 64; keep, pause 128...
    ReplayPolicy policy;
    std::vector<int> keptFrames;
    for (int f = 0; f < 250; ++f) {
        if (policy.Keep()) keptFrames.push_back(f);
        policy.AfterFrame(policy.Keep() ? 1000 : 0, policy.Keep() ? 1 : 0);
    }
    EXPECT_EQ(keptFrames, (std::vector<int>{0, 17, 50, 115, 244}));
}

TEST(ReplayPolicy, APayingFrameResetsThePause) {
    ReplayPolicy policy;
    policy.AfterFrame(1000, 1);  // pause 16
    for (int f = 0; f < ReplayPolicy::kFirstPause; ++f) {
        EXPECT_FALSE(policy.Keep());
        policy.AfterFrame(0, 0);
    }
    EXPECT_TRUE(policy.Keep());
    policy.AfterFrame(1000, 5000);  // pays: the next pause is the first again, not twice it
    EXPECT_TRUE(policy.Keep());
    policy.AfterFrame(1000, 1);
    int paused = 0;
    while (!policy.Keep()) {
        ++paused;
        policy.AfterFrame(0, 0);
    }
    EXPECT_EQ(paused, ReplayPolicy::kFirstPause);
}

}  // namespace
}  // namespace povrayfc
