// Tests for BlockHulls: a block's candidate hulls never leave out a hull one of its
// segments meets, and a narrow block sees few of many spread-out hulls.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "povrayfc/block_hulls.h"
#include "povrayfc/ray_recording.h"
#include "povrayfc/sample_store.h"
#include "povrayfc/segment_fans.h"

using namespace povrayfc;

namespace {

Vec3 Normalised(Vec3 v) {
    const double n = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
    return (1.0 / n) * v;
}

// What a block's recorder fills, and the cones built around it.
struct RecordedRays {
    std::vector<Segment> segments;
    std::vector<std::uint8_t> fanOf;
    std::vector<std::uint8_t> packed;
    FanApexes apexes;
    BlockFans fans;
    bool fansBuilt = false;
};

// A block's worth of rays as the hooks record them: camera rays from one eye in a narrow
// cone (some to infinity), a shadow test towards one light from every hit (some blocked),
// and a few reflections of finite length (loose segments).
RecordedRays RecordedBlock(std::mt19937_64 &rng, double spread) {
    std::uniform_real_distribution<double> u(-1, 1), len(5, 40);
    const Vec3 eye{0, 2, -20}, light{10, 25, -5};
    const Vec3 look = Normalised(Vec3{0.8 * u(rng), 0.3 * u(rng), 1});
    RecordedRays record;
    SampleRecorder recorder;
    StartRecordingRays(recorder);
    for (int i = 0; i < 300; ++i) {
        recorder.Begin(record.segments, record.fanOf, record.packed, record.apexes, nullptr, 0);
        const Vec3 d = Normalised(look + Vec3{spread * u(rng), spread * u(rng), 0});
        const bool hits = u(rng) > -0.7;
        const double t = hits ? len(rng) : 2e10;
        const double o[3] = {eye.x, eye.y, eye.z}, dd[3] = {d.x, d.y, d.z};
        RecordRaySegment(o, dd, t, kUnitNothing);
        if (!hits) continue;
        const Vec3 p = eye + t * d;
        const Vec3 toLight = light - p;
        const double dist = std::sqrt(toLight.x * toLight.x + toLight.y * toLight.y + toLight.z * toLight.z);
        const Vec3 l = (1.0 / dist) * toLight;
        {
            const double po[3] = {p.x, p.y, p.z}, ld[3] = {l.x, l.y, l.z};
            ShadowSegmentRecord shadow(po, ld, dist);
            if (i % 5 == 0) shadow.BlockedAt(dist * (0.3 + 0.6 * (u(rng) + 1) / 2), kUnitNothing, true);
        }
        if (i % 6 == 0) {
            const Vec3 r = Normalised(Vec3{u(rng), u(rng), u(rng)});
            const double po[3] = {p.x, p.y, p.z}, rd[3] = {r.x, r.y, r.z};
            RecordRaySegment(po, rd, len(rng) / 4, kUnitNothing);
        }
    }
    StopRecordingRays();
    record.fans = BuildFans(record.segments.data(), record.fanOf, record.apexes);
    record.fansBuilt = true;
    return record;
}

// Many small hulls spread over the whole scene, as when a pattern changes on hundreds of
// tiles: their union covers everything, so only per-hull tests can reject anything.
std::vector<Hull> SpreadHulls(std::mt19937_64 &rng, int count, double size) {
    std::uniform_real_distribution<double> x(-25, 25), y(-2, 25), z(-5, 45);
    std::vector<Hull> hulls;
    for (int i = 0; i < count; ++i) {
        Hull h;
        const Vec3 c{x(rng), y(rng), z(rng)};
        h.box = Box{c - Vec3{size, size, size}, c + Vec3{size, size, size}};
        hulls.push_back(h);
    }
    return hulls;
}

bool BruteForceMayMeet(const Segment &s, const std::vector<Hull> &hulls) {
    for (const Hull &h : hulls)
        if (MayMeet(s, h)) return true;
    return false;
}

TEST(BlockHulls, NeverLeavesOutAHullASegmentMeets) {
    std::mt19937_64 rng(11);
    int meets = 0, rejected = 0;
    for (int trial = 0; trial < 60; ++trial) {
        const RecordedRays record = RecordedBlock(rng, trial % 2 ? 0.02 : 0.3);
        const int count = trial % 3 == 0 ? 8 : (trial % 3 == 1 ? 200 : 700);
        const std::vector<Hull> hulls = SpreadHulls(rng, count, trial % 4 == 0 ? 3.0 : 0.4);
        const ChangeIndex changes(hulls);
        const BlockHulls reach = FindBlockHulls(record.fans, changes);
        for (std::size_t i = 0; i < record.segments.size(); ++i) {
            const Segment &s = record.segments[i];
            const bool truth = BruteForceMayMeet(s, changes.Hulls());
            const bool claimed = reach.SegmentMayMeet(s, record.fanOf[i], changes);
            // Invariant: conservative, never a miss.
            if (truth) {
                ASSERT_TRUE(claimed) << "trial " << trial << " segment " << i;
                ++meets;
            } else if (!claimed) {
                ++rejected;
            }
        }
    }
    EXPECT_GT(meets, 100);
    EXPECT_GT(rejected, 1000);
}

TEST(BlockHulls, ANarrowBlockListsFewOfManySpreadHulls) {
    std::mt19937_64 rng(5);
    const RecordedRays record = RecordedBlock(rng, 0.01);
    const ChangeIndex changes(SpreadHulls(rng, 300, 0.3));
    ASSERT_TRUE(changes.HasGrid());
    const BlockHulls reach = FindBlockHulls(record.fans, changes);
    // The point of the per-block list: a handful of candidates, not "all" (the grid walk).
    EXPECT_FALSE(reach.all);
    EXPECT_LT(reach.count, 64u);
}

TEST(BlockHulls, NoChangeNearTheBlockNeedsNoSegmentTest) {
    std::mt19937_64 rng(9);
    const RecordedRays record = RecordedBlock(rng, 0.01);
    Hull far;
    far.box = Box{Vec3{500, 500, 500}, Vec3{501, 501, 501}};
    const ChangeIndex changes(std::vector<Hull>{far});
    EXPECT_FALSE(FindBlockHulls(record.fans, changes).Any());
}

TEST(BlockHulls, MoreCandidatesThanAMaskHoldsFallBackToTheWholeIndex) {
    std::mt19937_64 rng(21);
    const RecordedRays record = RecordedBlock(rng, 0.5);
    // Big hulls everywhere: every fan reaches far more than 64 of them.
    const ChangeIndex changes(SpreadHulls(rng, 400, 4.0));
    const BlockHulls reach = FindBlockHulls(record.fans, changes);
    EXPECT_TRUE(reach.all);
    EXPECT_TRUE(reach.Any());
    for (std::size_t i = 0; i < record.segments.size(); ++i) {
        if (!BruteForceMayMeet(record.segments[i], changes.Hulls())) continue;
        ASSERT_TRUE(reach.SegmentMayMeet(record.segments[i], record.fanOf[i], changes));
    }
}

}  // namespace
