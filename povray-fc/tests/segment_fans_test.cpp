// Tests for SegmentFans: a fan's cone never misses a hull that one of its segments meets.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "povrayfc/ray_recording.h"
#include "povrayfc/segment_fans.h"

using namespace povrayfc;

namespace {

Vec3 Normalised(Vec3 v) {
    const double n = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
    return (1.0 / n) * v;
}

struct RecordedBlock {
    std::vector<Segment> segments;
    std::vector<std::uint8_t> fanOf;
    FanApexes apexes;
};

// A block's worth of rays recorded as the hooks record them: camera rays from one eye
// (some to infinity), a shadow test from each hit towards one of two lights (some stopped
// by a blocker half way), and a few reflections.
RecordedBlock BlockRays(std::mt19937_64 &rng) {
    std::uniform_real_distribution<double> u(-1, 1), len(2, 30);
    const Vec3 eye{0.3, 2, -20}, lights[2] = {Vec3{10, 15, -5}, Vec3{-7, 12, 3}};
    const Vec3 look = Normalised(Vec3{u(rng), 0.3 * u(rng), 1});
    RecordedBlock b;
    SampleRecorder recorder;
    StartRecordingRays(recorder);
    for (int i = 0; i < 200; ++i) {
        recorder.Begin(b.segments, b.fanOf, b.apexes);
        const Vec3 d = Normalised(look + Vec3{0.05 * u(rng), 0.05 * u(rng), 0});
        const bool hits = u(rng) > -0.6;
        const double t = hits ? len(rng) : 2e10;
        const double o[3] = {eye.x, eye.y, eye.z}, dd[3] = {d.x, d.y, d.z};
        RecordRaySegment(o, dd, t);
        if (!hits) continue;
        const Vec3 p = eye + t * d;
        const Vec3 toLight = lights[i % 2] - p;
        const double dist = std::sqrt(toLight.x * toLight.x + toLight.y * toLight.y + toLight.z * toLight.z);
        const Vec3 l = (1.0 / dist) * toLight;
        {
            const double po[3] = {p.x, p.y, p.z}, ld[3] = {l.x, l.y, l.z};
            ShadowSegmentRecord shadow(po, ld, dist);
            if (i % 5 == 0) shadow.BlockedAt(dist * (0.5 + 0.4 * u(rng)));
        }
        if (i % 7 == 0) {
            const Vec3 r = Normalised(Vec3{u(rng), u(rng), u(rng)});
            const double po[3] = {p.x, p.y, p.z}, rd[3] = {r.x, r.y, r.z};
            RecordRaySegment(po, rd, len(rng));
        }
    }
    StopRecordingRays();
    return b;
}

TEST(SegmentFans, BundlesTheCameraAndTheLights) {
    std::mt19937_64 rng(3);
    RecordedBlock b = BlockRays(rng);
    const std::size_t n = b.segments.size();
    const BlockFans fans = BuildFans(b.segments.data(), b.fanOf, b.apexes);
    // Invariant: camera rays and shadow rays are bundled (camera, two lights); the random
    // reflections share no point, so they stay loose.
    ASSERT_EQ(fans.fans.size(), 3u);
    EXPECT_EQ(fans.fans[0].originReach, 0.0);
    EXPECT_GT(fans.fans[1].originReach, 0.0);
    EXPECT_GT(fans.looseCount, 0u);
    EXPECT_LT(fans.looseCount, n / 8);
}

TEST(SegmentFans, ConeNeverMissesAHullItsSegmentsMeet) {
    std::mt19937_64 rng(17);
    std::uniform_real_distribution<double> pos(-15, 15), size(0.05, 3);
    int checked = 0, fanRejects = 0;
    for (int block = 0; block < 200; ++block) {
        RecordedBlock b = BlockRays(rng);
        const BlockFans fans = BuildFans(b.segments.data(), b.fanOf, b.apexes);
    const std::vector<std::uint8_t> &fanOf = b.fanOf;
        for (int k = 0; k < 200; ++k) {
            const Vec3 lo{pos(rng), pos(rng) * 0.5 + 5, pos(rng)};
            const Hull h = MakeHull(Box{lo, lo + Vec3{size(rng), size(rng), size(rng)}});
            for (std::size_t f = 0; f < fans.fans.size(); ++f) {
                const bool cone = FanMayMeet(fans.fans[f], h);
                fanRejects += !cone;
                for (std::size_t i = 0; i < b.segments.size(); ++i) {
                    if (fanOf[i] != f || !MayMeet(b.segments[i], h)) continue;
                    ++checked;
                    ASSERT_TRUE(cone) << "block " << block << " fan " << f << " segment " << i;
                }
            }
        }
    }
    EXPECT_GT(checked, 10000);
    EXPECT_GT(fanRejects, 10000);  // the cones do reject most hulls
}

TEST(SegmentFans, GrowingAFanKeepsHoldingItsSegments) {
    std::mt19937_64 rng(23);
    std::uniform_real_distribution<double> pos(-15, 15), size(0.05, 3);
    for (int block = 0; block < 50; ++block) {
        RecordedBlock a = BlockRays(rng), b = BlockRays(rng);
        BlockFans fans = BuildFans(a.segments.data(), a.fanOf, a.apexes);
        // b's rays join a's block, as newly traced samples join a replayed block.
        const std::size_t first = a.segments.size();
        SampleRecorder recorder;
        recorder.Begin(a.segments, a.fanOf, a.apexes);
        for (const Segment &s : b.segments) {
            a.segments.push_back(s);
            a.fanOf.push_back(BlockFans::kLoose);
        }
        // Reassign b's segments as the recorder would have against a's apexes.
        for (std::size_t i = first; i < a.segments.size(); ++i) {
            const Segment &s = a.segments[i];
            const double o[3] = {s.origin[0], s.origin[1], s.origin[2]};
            a.fanOf[i] = a.apexes.OriginFan(o);
        }
        const BlockFans grown = GrowFans(fans, a.segments.data(), a.fanOf, a.apexes, {{first, a.segments.size() - first}});
        const std::vector<std::uint8_t> &fanOf = a.fanOf;
        for (int k = 0; k < 100; ++k) {
            const Vec3 lo{pos(rng), pos(rng) * 0.5 + 5, pos(rng)};
            const Hull h = MakeHull(Box{lo, lo + Vec3{size(rng), size(rng), size(rng)}});
            for (std::size_t i = 0; i < a.segments.size(); ++i) {
                const std::uint8_t f = fanOf[i];
                // Invariant: old and new members alike stay inside their (grown) cone.
                if (f != BlockFans::kLoose && MayMeet(a.segments[i], h)) {
                    ASSERT_TRUE(FanMayMeet(grown.fans[f], h)) << block << " " << i;
                }
            }
        }
    }
}

}  // namespace
