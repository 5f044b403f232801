#include "povrayfc/replay_policy.h"

#include <vector>

#include <gtest/gtest.h>

namespace povrayfc {
namespace {

// How many of `frames` frames keep replays when every frame tries `tried` and keeps `kept`
// (a frame that keeps none tries none the next).
int FramesKeeping(int frames, std::uint64_t tried, std::uint64_t kept) {
    ReplayPolicy policy;
    int keeping = 0;
    for (int f = 0; f < frames; ++f) {
        const bool keep = policy.Keep();
        keeping += keep;
        policy.AfterFrame(keep ? tried : 0, keep ? kept : 0);
    }
    return keeping;
}

TEST(ReplayPolicy, KeepsWhileTriesPay) {
    EXPECT_EQ(FramesKeeping(100, 1000, 250), 100);
    EXPECT_EQ(FramesKeeping(100, 1000, 900), 100);
    // Frames with nothing to try say nothing.
    EXPECT_EQ(FramesKeeping(100, 0, 0), 100);
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
    policy.AfterFrame(1000, 500);  // pays: the next pause is the first again, not twice it
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
