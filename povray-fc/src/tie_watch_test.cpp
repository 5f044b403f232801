// Tests for TieWatch: which searches for a nearest intersection hang on object order.
#include <gtest/gtest.h>

#include <vector>

#include "povrayfc/ray_recording.h"
#include "povrayfc/tie_watch.h"

namespace povrayfc {
namespace {

// Runs `search` as one recorded sample and says whether the sample came out order-sensitive.
template <class Search>
bool OrderSensitive(Search search) {
    std::vector<Segment> segments;
    std::vector<std::uint8_t> fans;
    std::vector<std::uint8_t> packed;
    FanApexes apexes;
    SampleRecorder recorder;
    recorder.Begin(segments, fans, packed, apexes, nullptr, 0);
    StartRecordingRays(recorder);
    search();
    StopRecordingRays();
    return recorder.OrderSensitive();
}

const double kDirection[3] = {0.0, 0.6, 0.8};

TEST(TieWatch, TwoCandidatesAtTheBestDepthAreATie) {
    // Invariant: equal depths of two objects make the answer depend on which came first.
    EXPECT_TRUE(OrderSensitive([] {
        double best = 1e30;
        TieWatch watch(kDirection, best);
        for (double t : {3.0, 2.0, 2.0}) {
            NoteTieCandidate(t);
            if (t < best) best = t;
        }
    }));
}

TEST(TieWatch, DistinctDepthsAndTiesBehindTheBestAreNot) {
    // Invariant: the nearest of distinct depths is the same in any order; a tie behind the
    // best depth decides nothing.
    EXPECT_FALSE(OrderSensitive([] {
        double best = 1e30;
        TieWatch watch(kDirection, best);
        for (double t : {2.0, std::nextafter(2.0, 3.0), 5.0, 5.0}) {
            NoteTieCandidate(t);
            if (t < best) best = t;
        }
    }));
}

TEST(TieWatch, ABoxSkippedJustBehindTheBestDepthIsATie) {
    // Invariant: an object whose float box begins within rounding behind the best depth may
    // reach it; another tree might have tried it first.
    EXPECT_TRUE(OrderSensitive([] {
        double best = 1e30;
        TieWatch watch(kDirection, best);
        NoteTieCandidate(2.0);
        best = 2.0;
        NoteTieSkipped(2.0 + 1e-7, 10.0);
    }));
    EXPECT_FALSE(OrderSensitive([] {
        double best = 1e30;
        TieWatch watch(kDirection, best);
        NoteTieCandidate(2.0);
        best = 2.0;
        NoteTieSkipped(2.1, 10.0);
    }));
}

TEST(TieWatch, TheSlackGrowsWithTheBoxesAndAGrazingDirection) {
    // Invariant: float rounding of larger coordinates, met at a grazing angle, moves a
    // box's entry farther along the ray.
    double best = 0;
    std::vector<Segment> segments;
    std::vector<std::uint8_t> fans;
    std::vector<std::uint8_t> packed;
    FanApexes apexes;
    SampleRecorder recorder;
    recorder.Begin(segments, fans, packed, apexes, nullptr, 0);
    StartRecordingRays(recorder);
    const double steep[3] = {0.0, 0.6, 0.8}, grazing[3] = {0.001, 0.6, 0.8};
    TieWatch a(steep, best), b(grazing, best);
    EXPECT_LT(a.SkipSlack(10.0), a.SkipSlack(1000.0));
    EXPECT_LT(a.SkipSlack(10.0), b.SkipSlack(10.0));
    // At least the float rounding of a box corner, 2^-24 of its magnitude, over the
    // direction component it is crossed along.
    EXPECT_GE(a.SkipSlack(1000.0), std::ldexp(1000.0, -23) / 0.6);
    StopRecordingRays();
}

TEST(TieWatch, InnermostWatchTakesTheNotesAndNothingHappensWithoutRecording) {
    // Invariant: without a recording sample the hooks do nothing; nested searches do not
    // mix their candidates.
    double best = 1e30;
    {
        TieWatch idle(kDirection, best);
        EXPECT_FALSE(TieWatchOpen());
        NoteTieCandidate(1.0);
    }
    EXPECT_FALSE(OrderSensitive([] {
        double outerBest = 1.0, innerBest = 1e30;
        TieWatch outer(kDirection, outerBest);
        NoteTieCandidate(1.0);
        {
            TieWatch inner(kDirection, innerBest);
            NoteTieCandidate(1.0);  // the inner search's only candidate
            innerBest = 1.0;
        }
    }));
}

// Runs `search` as one recorded sample of a frame with units 0..2 (ids 10, 11, 12) and
// gives the tied searches it packed (false: packed as not replayable).
template <class Search>
bool PackedTies(Search search, std::vector<TiedSearch> &ties) {
    std::vector<Segment> segments;
    std::vector<std::uint8_t> fans;
    std::vector<std::uint8_t> packed;
    FanApexes apexes;
    SampleRecorder recorder;
    const std::uint32_t ids[3] = {10, 11, 12};
    recorder.Begin(segments, fans, packed, apexes, ids, 3);
    StartRecordingRays(recorder);
    search();
    StopRecordingRays();
    EXPECT_TRUE(recorder.OrderSensitive());
    recorder.PackTies();
    EXPECT_EQ(packed.size(), TiedSearchesBytes(packed.data()));
    return UnpackTiedSearches(packed.data(), ties);
}

// A describer answering from a Described: what the hook would read off POV-Ray's search.
struct Described {
    bool describable;
    std::uint32_t unitIndex;
    std::uint64_t hash;
    int asked = 0;
};
bool Describe(const void *context, TiedSearch &search, std::uint32_t &unitIndex) {
    Described &d = *const_cast<Described *>(static_cast<const Described *>(context));
    ++d.asked;
    search.kind = 2;
    search.rayFlags = 0x11;
    search.origin[0] = 1.0;
    search.origin[1] = -2.0;
    search.origin[2] = 0.5;
    search.objectHash = d.hash;
    unitIndex = d.unitIndex;
    return d.describable;
}

TEST(TieWatch, ATiedSearchIsDescribedWhenDoneAndKeptToRunAgain) {
    std::vector<TiedSearch> ties;
    Described found{true, 1, 0xabc};
    ASSERT_TRUE(PackedTies(
        [&] {
            double best = 1e7;
            TieWatch watch(kDirection, best, &Describe, &found);
            NoteTieCandidate(4.0);
            best = 4.0;
            NoteTieCandidate(4.0);
        },
        ties));
    EXPECT_EQ(found.asked, 1);
    ASSERT_EQ(ties.size(), 1u);
    EXPECT_EQ(ties[0].kind, 2);
    EXPECT_EQ(ties[0].rayFlags, 0x11);
    EXPECT_EQ(ties[0].origin[1], -2.0);
    EXPECT_EQ(ties[0].direction[2], kDirection[2]);
    EXPECT_EQ(ties[0].start, 1e7);  // the bound it started from
    EXPECT_EQ(ties[0].depth, 4.0);  // what it ended with
    EXPECT_EQ(ties[0].unit, 11u);   // the unit's id, not the parser's index
    EXPECT_EQ(ties[0].objectHash, 0xabcu);

    // A search that did not end in a tie is never described.
    Described untied{true, 1, 0xabc};
    EXPECT_FALSE(OrderSensitive([&] {
        double best = 1e7;
        TieWatch watch(kDirection, best, &Describe, &untied);
        NoteTieCandidate(4.0);
        best = 4.0;
        NoteTieCandidate(5.0);
    }));
    EXPECT_EQ(untied.asked, 0);
}

TEST(TieWatch, ATiedSearchThatCannotBeToldApartOrRunAgainMakesTheSampleUnreplayable) {
    std::vector<TiedSearch> ties;
    auto tied = [](Described *described) {
        return [described] {
            double best = 3.0;
            TieWatch watch(kDirection, best, described ? &Describe : nullptr, described);
            NoteTieCandidate(3.0);
            NoteTieCandidate(3.0);
        };
    };
    // No describer, or one that cannot describe it (another kind of search).
    EXPECT_FALSE(PackedTies(tied(nullptr), ties));
    Described cannot{false, 1, 5};
    EXPECT_FALSE(PackedTies(tied(&cannot), ties));
    // Found an object without a hash of its own, or without a unit fc knows.
    Described noHash{true, 0, 0}, noUnit{true, 7, 5};
    EXPECT_FALSE(PackedTies(tied(&noHash), ties));
    EXPECT_FALSE(PackedTies(tied(&noUnit), ties));
    // Found nothing: kept, with no unit.
    Described nothing{true, kUnitNothing, 0};
    ASSERT_TRUE(PackedTies(tied(&nothing), ties));
    ASSERT_EQ(ties.size(), 1u);
    EXPECT_EQ(ties[0].unit, Segment::kNoUnit);
}

}  // namespace
}  // namespace povrayfc
