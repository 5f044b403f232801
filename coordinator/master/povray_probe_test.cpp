// povray_probe_test.cpp - unit tests of what fc-master makes of POV-Ray's resolved options.
#include <vector>

#include <gtest/gtest.h>

#include "povray_probe.h"

using namespace fc;

// The frames come from the resolved options alone, whatever frame the console's output name
// had (newton-table once got 44 of 45 frames when it named frame 2).
TEST(PovrayProbe, FramesFromResolvedOptions)
{
    auto frames = [](const ResolvedOptions &ini, int console_first) {
        SceneInfo info;
        info.animated = true;
        info.first_frame = console_first;
        std::string err;
        EXPECT_TRUE(set_frames(info, ini, err));
        return info.frames;
    };
    ResolvedOptions newton = {{"Initial_Frame", "1"}, {"Final_Frame", "45"},
                              {"Subset_Start_Frame", "1"}, {"Subset_End_Frame", "45"}};
    std::vector<int> all = frames(newton, 2);
    EXPECT_TRUE(all.size() == 45 && all.front() == 1 && all.back() == 45);
    EXPECT_TRUE(frames({{"Initial_Frame", "1"}, {"Final_Frame", "45"}}, 7).front() == 1);
    // Subsets as frames and as fractions, as AnimationProcessing computes them.
    std::vector<int> sub = frames({{"Initial_Frame", "1"}, {"Final_Frame", "20"},
                                   {"Subset_Start_Frame", "5"}, {"Subset_End_Frame", "8"}}, 1);
    EXPECT_TRUE((sub == std::vector<int>{5, 6, 7, 8}));
    std::vector<int> half = frames({{"Initial_Frame", "1"}, {"Final_Frame", "20"},
                                    {"Subset_Start_Frame", "0.5"}}, 1);
    EXPECT_TRUE(half.front() == 10 && half.back() == 20);
    // A start before Initial_Frame starts at it.
    EXPECT_TRUE(frames({{"Initial_Frame", "3"}, {"Final_Frame", "9"}, {"Subset_Start_Frame", "2"}}, 1)
              .front() == 3);
}
