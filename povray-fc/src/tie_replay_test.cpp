// Tests for tied searches kept with a sample and run again (tie_replay.h).
#include "povrayfc/tie_replay.h"

#include <cstring>
#include <vector>

#include <gtest/gtest.h>

#include "povrayfc/scene_signature.h"
#include "povrayfc/segment.h"

namespace povrayfc {
namespace {

TiedSearch Search(std::uint8_t kind, double depth, std::uint32_t unit, std::uint64_t hash) {
    TiedSearch s{};
    s.kind = kind;
    s.rayFlags = 0x15;
    s.origin[0] = 0.1;
    s.origin[1] = -2.5;
    s.origin[2] = 1e-300;
    s.direction[0] = 0.6;
    s.direction[1] = 0.0;
    s.direction[2] = -0.8;
    s.start = 1e7;
    s.depth = depth;
    s.unit = unit;
    s.objectHash = hash;
    return s;
}

// Answers each search with what `answers` holds for it, in order, and keeps what it was asked.
class ScriptedReplayer : public TieReplayer {
  public:
    struct Answer {
        double depth;
        std::uint32_t unitIndex;
        std::uint64_t hash;
        bool ok = true;
    };
    std::vector<Answer> answers;
    std::vector<TiedSearch> asked;

    bool Replay(const TiedSearch &search, double &depth, std::uint32_t &unitIndex, std::uint64_t &hash) override {
        const Answer &a = answers.at(asked.size());
        asked.push_back(search);
        depth = a.depth;
        unitIndex = a.unitIndex;
        hash = a.hash;
        return a.ok;
    }
};

// This frame's units: index i has id 100 + i; index 3 has no id fc knows.
const std::uint32_t kUnitIds[4] = {100, 101, 102, Segment::kOpaqueBlocker | 7};

TEST(TieReplay, SearchesPackAfterWhatIsThereAndReadBackExactly) {
    std::vector<std::uint8_t> packed = {9, 9, 9};
    const std::vector<TiedSearch> searches = {Search(1, 2.25, 101, 77), Search(2, 1e7, Segment::kNoUnit, 0)};
    PackTiedSearches(searches, true, packed);
    ASSERT_EQ(packed.size(), 3 + TiedSearchesBytes(packed.data() + 3));
    EXPECT_EQ(TiedSearchesBytes(packed.data() + 3), 1 + 2 * kTiedSearchBytes);
    std::vector<TiedSearch> back;
    ASSERT_TRUE(UnpackTiedSearches(packed.data() + 3, back));
    ASSERT_EQ(back.size(), 2u);
    for (std::size_t i = 0; i < 2; ++i) {
        EXPECT_EQ(back[i].kind, searches[i].kind);
        EXPECT_EQ(back[i].rayFlags, searches[i].rayFlags);
        EXPECT_EQ(std::memcmp(back[i].origin, searches[i].origin, sizeof back[i].origin), 0);
        EXPECT_EQ(std::memcmp(back[i].direction, searches[i].direction, sizeof back[i].direction), 0);
        EXPECT_EQ(back[i].start, searches[i].start);
        EXPECT_EQ(back[i].depth, searches[i].depth);
        EXPECT_EQ(back[i].unit, searches[i].unit);
        EXPECT_EQ(back[i].objectHash, searches[i].objectHash);
    }
}

TEST(TieReplay, IncompleteOrTooManySearchesCannotBeRunAgain) {
    std::vector<std::uint8_t> packed;
    PackTiedSearches({Search(1, 2.0, 100, 1)}, false, packed);
    EXPECT_EQ(TiedSearchesBytes(packed.data()), 1u);
    ScriptedReplayer replayer;
    EXPECT_FALSE(TiedSearchesHold(packed.data(), &replayer, kUnitIds, 4));
    EXPECT_TRUE(replayer.asked.empty());

    packed.clear();
    PackTiedSearches(std::vector<TiedSearch>(kMaxTiedSearches + 1, Search(1, 2.0, 100, 1)), true, packed);
    EXPECT_EQ(TiedSearchesBytes(packed.data()), 1u);
    EXPECT_FALSE(TiedSearchesHold(packed.data(), &replayer, kUnitIds, 4));

    // No replayer: nothing can be run again.
    packed.clear();
    PackTiedSearches({Search(1, 2.0, 100, 1)}, true, packed);
    EXPECT_FALSE(TiedSearchesHold(packed.data(), nullptr, kUnitIds, 4));
}

TEST(TieReplay, SearchesHoldOnlyWhenEachFindsTheSameObjectAtTheSameDepth) {
    std::vector<std::uint8_t> packed;
    PackTiedSearches({Search(1, 2.5, 101, 55), Search(2, 1e7, Segment::kNoUnit, 0)}, true, packed);
    auto holds = [&](std::vector<ScriptedReplayer::Answer> answers, std::size_t expectAsked) {
        ScriptedReplayer replayer;
        replayer.answers = answers;
        const bool held = TiedSearchesHold(packed.data(), &replayer, kUnitIds, 4);
        EXPECT_EQ(replayer.asked.size(), expectAsked);
        // Asked exactly as kept, in order.
        if (!replayer.asked.empty()) {
            EXPECT_EQ(replayer.asked[0].kind, 1);
            EXPECT_EQ(replayer.asked[0].rayFlags, 0x15);
            EXPECT_EQ(replayer.asked[0].start, 1e7);
            EXPECT_EQ(replayer.asked[0].origin[2], 1e-300);
        }
        return held;
    };
    const std::uint32_t nothing = kUnitNothing;
    // Unit index 1 is id 101 this frame.
    EXPECT_TRUE(holds({{2.5, 1, 55}, {1e7, nothing, 0}}, 2));
    // Another unit, another part of the unit, another depth (even by one ulp or its sign).
    EXPECT_FALSE(holds({{2.5, 2, 55}, {1e7, nothing, 0}}, 1));
    EXPECT_FALSE(holds({{2.5, 1, 56}, {1e7, nothing, 0}}, 1));
    EXPECT_FALSE(holds({{std::nextafter(2.5, 3.0), 1, 55}, {1e7, nothing, 0}}, 1));
    EXPECT_FALSE(holds({{2.5, 1, 55}, {1e7, 0, 0}}, 2));  // now finds something
    EXPECT_FALSE(holds({{2.5, 1, 55}, {9e6, nothing, 0}}, 2));
    // An object without an id fc knows, an index past the frame's units, a failed search.
    EXPECT_FALSE(holds({{2.5, 3, 55}, {1e7, nothing, 0}}, 1));
    EXPECT_FALSE(holds({{2.5, 4, 55}, {1e7, nothing, 0}}, 1));
    EXPECT_FALSE(holds({{2.5, 1, 55, false}, {1e7, nothing, 0}}, 1));

    packed.clear();
    PackTiedSearches({Search(1, 0.0, 101, 55)}, true, packed);
    EXPECT_FALSE(holds({{-0.0, 1, 55}}, 1));
    EXPECT_TRUE(holds({{0.0, 1, 55}}, 1));
}

}  // namespace
}  // namespace povrayfc
