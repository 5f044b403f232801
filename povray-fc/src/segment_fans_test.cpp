// Tests for SegmentFans: a fan's cone never misses a hull that one of its segments meets.
#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "povrayfc/ray_recording.h"
#include "povrayfc/segment_fans.h"

using namespace povrayfc;

namespace {

double Norm3(Vec3 v) { return std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z); }

Vec3 Normalised(Vec3 v) {
    const double n = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
    return (1.0 / n) * v;
}

struct RecordedBlock {
    std::vector<Segment> segments;
    std::vector<std::uint8_t> fanOf;
    std::vector<std::uint8_t> packed;
    FanApexes apexes;
};

// A block's worth of rays recorded as the hooks record them: camera rays from one eye
// (some to infinity), a shadow test from each hit towards one of two lights (some stopped
// by a blocker half way), and a few reflections, each with a shadow test from its hit.
RecordedBlock BlockRays(std::mt19937_64 &rng) {
    std::uniform_real_distribution<double> u(-1, 1), len(2, 30);
    const Vec3 eye{0.3, 2, -20}, lights[2] = {Vec3{10, 15, -5}, Vec3{-7, 12, 3}};
    const Vec3 look = Normalised(Vec3{u(rng), 0.3 * u(rng), 1});
    RecordedBlock b;
    SampleRecorder recorder;
    StartRecordingRays(recorder);
    for (int i = 0; i < 200; ++i) {
        recorder.Begin(b.segments, b.fanOf, b.packed, b.apexes, nullptr, 0);
        const Vec3 d = Normalised(look + Vec3{0.05 * u(rng), 0.05 * u(rng), 0});
        const bool hits = u(rng) > -0.6;
        const double t = hits ? len(rng) : 2e10;
        const double o[3] = {eye.x, eye.y, eye.z}, dd[3] = {d.x, d.y, d.z};
        RecordRaySegment(o, dd, t, kUnitNothing);
        if (!hits) continue;
        const Vec3 p = eye + t * d;
        const Vec3 toLight = lights[i % 2] - p;
        const double dist = std::sqrt(toLight.x * toLight.x + toLight.y * toLight.y + toLight.z * toLight.z);
        const Vec3 l = (1.0 / dist) * toLight;
        {
            const double po[3] = {p.x, p.y, p.z}, ld[3] = {l.x, l.y, l.z};
            ShadowSegmentRecord shadow(po, ld, dist);
            if (i % 5 == 0) shadow.BlockedAt(dist * (0.5 + 0.4 * u(rng)), kUnitNothing, true);
        }
        if (i % 7 == 0) {
            const Vec3 r = Normalised(Vec3{u(rng), u(rng), u(rng)});
            const double po[3] = {p.x, p.y, p.z}, rd[3] = {r.x, r.y, r.z}, rt = len(rng);
            RecordRaySegment(po, rd, rt, kUnitNothing);
            const Vec3 q = p + rt * r, toOther = lights[(i + 1) % 2] - q;
            const double qDist = Norm3(toOther);
            const Vec3 ql = (1.0 / qDist) * toOther;
            const double qo[3] = {q.x, q.y, q.z}, qd[3] = {ql.x, ql.y, ql.z};
            ShadowSegmentRecord deepShadow(qo, qd, qDist);
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
    // Invariant: camera rays and shadow rays are bundled (camera, two lights, and the two
    // lights again for the shadow tests from where reflections hit); the random
    // reflections share no point, so they stay loose.
    ASSERT_EQ(fans.fans.size(), 5u);
    EXPECT_EQ(fans.fans[0].originReach, 0.0);
    EXPECT_GT(fans.fans[1].originReach, 0.0);
    int deep = 0;
    for (int f = 0; f < b.apexes.count; ++f) deep += b.apexes.isDeep[f];
    EXPECT_EQ(deep, 2);
    // The shadow tests from the camera rays' hits lie in a narrower cone than those from
    // the reflections' hits, which come from all around.
    for (int f = 1; f < b.apexes.count; ++f)
        for (int g = 1; g < b.apexes.count; ++g)
            if (!b.apexes.isDeep[f] && b.apexes.isDeep[g] && Norm3(Vec3{b.apexes.point[f][0] - b.apexes.point[g][0],
                    b.apexes.point[f][1] - b.apexes.point[g][1], b.apexes.point[f][2] - b.apexes.point[g][2]}) < 1e-6) {
                EXPECT_LT(fans.fans[std::size_t(f)].halfAngle, fans.fans[std::size_t(g)].halfAngle);
            }
    const std::size_t loose = std::size_t(std::count(b.fanOf.begin(), b.fanOf.end(), BlockFans::kLoose));
    EXPECT_GT(loose, 0u);
    EXPECT_LT(loose, n / 8);
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

// Slanted thin cylinders (strings, rods) and spheres, as capsule hulls: the cone's test
// against the capsule must hold every member that meets it, and reject blocks that only
// the capsule's box reaches.
TEST(SegmentFans, ConeNeverMissesACapsuleItsSegmentsMeet) {
    std::mt19937_64 rng(29);
    std::uniform_real_distribution<double> pos(-15, 15), unit(-1, 1), radius(0.01, 1.5);
    int checked = 0, boxOnly = 0, capsuleRejects = 0;
    for (int block = 0; block < 200; ++block) {
        RecordedBlock b = BlockRays(rng);
        const BlockFans fans = BuildFans(b.segments.data(), b.fanOf, b.apexes);
        for (int k = 0; k < 200; ++k) {
            const Vec3 a{pos(rng), pos(rng) * 0.5 + 5, pos(rng)};
            // Every fifth a sphere (a capsule of no length), the others up to 12 long.
            const Vec3 axis = k % 5 == 0 ? Vec3{0, 0, 0} : 6.0 * Vec3{unit(rng), unit(rng), unit(rng)};
            const Capsule c{a, a + axis, k % 2 ? 0.03 : radius(rng)};
            Box box;
            box.Grow(c.a - Vec3{c.radius, c.radius, c.radius});
            box.Grow(c.b + Vec3{c.radius, c.radius, c.radius});
            box.Grow(c.a + Vec3{c.radius, c.radius, c.radius});
            box.Grow(c.b - Vec3{c.radius, c.radius, c.radius});
            const Hull capsule = MakeHull(box, c), boxed = MakeHull(box);
            for (std::size_t f = 0; f < fans.fans.size(); ++f) {
                const bool cone = FanMayMeet(fans.fans[f], capsule);
                const bool coneOfBox = FanMayMeet(fans.fans[f], boxed);
                // Invariant: the capsule only narrows the box's test.
                ASSERT_TRUE(coneOfBox || !cone) << block << " " << k << " " << f;
                // (The shadow tests from the random reflections' hits come from all
                // around: their cones reach every hull, box or capsule.)
                if (!b.apexes.isDeep[f]) {
                    boxOnly += coneOfBox;
                    capsuleRejects += coneOfBox && !cone;
                }
                for (std::size_t i = 0; i < b.segments.size(); ++i) {
                    if (b.fanOf[i] != f || !MayMeet(b.segments[i], capsule)) continue;
                    ++checked;
                    ASSERT_TRUE(cone) << "block " << block << " capsule " << k << " fan " << f << " segment " << i;
                }
            }
        }
    }
    EXPECT_GT(checked, 5000);
    EXPECT_GT(capsuleRejects, boxOnly / 10);  // the capsule rejects many that the box keeps
}

// Grazing cases: segments from the apex aimed at a capsule's surface, just inside and
// just outside, from all sides and along its axis.
TEST(SegmentFans, ConeHoldsRaysThatGrazeACapsule) {
    std::mt19937_64 rng(31);
    std::uniform_real_distribution<double> unit(-1, 1), t01(0, 1);
    int grazing = 0;
    for (int k = 0; k < 20000; ++k) {
        const Vec3 apex{10 * unit(rng), 10 * unit(rng), 10 * unit(rng)};
        const Vec3 a{5 * unit(rng), 5 * unit(rng), 5 * unit(rng)};
        const Vec3 axis = (k % 3 == 0) ? Vec3{0, 0, 0} : 4.0 * Vec3{unit(rng), unit(rng), unit(rng)};
        const Capsule c{a, a + axis, 0.001 + 0.5 * t01(rng)};
        // A point on the capsule's surface: a point of its axis plus a radius in a
        // random direction.
        const Vec3 p = a + t01(rng) * axis;
        const Vec3 r = Normalised(Vec3{unit(rng), unit(rng), unit(rng)});
        const Vec3 target = p + (c.radius * (1.0 - 1e-7)) * r;
        if (Norm3(target - apex) <= c.radius) continue;
        Box box;
        for (double s : {-1.0, 1.0}) {
            box.Grow(c.a + s * Vec3{c.radius, c.radius, c.radius});
            box.Grow(c.b + s * Vec3{c.radius, c.radius, c.radius});
        }
        const Hull hull = MakeHull(box, c);
        // One segment from the apex to the target and on: a cone of it alone.
        const Vec3 d = Normalised(target - apex);
        Segment seg;
        for (int i = 0; i < 3; ++i) {
            seg.origin[i] = float(apex[i]);
            seg.direction[i] = float(d[i]);
        }
        seg.length = float(1.5 * Norm3(target - apex));
        std::vector<std::uint8_t> fanOf{0};
        FanApexes apexes;
        const double o[3] = {seg.origin[0], seg.origin[1], seg.origin[2]};
        apexes.OriginFan(o);
        const BlockFans fans = BuildFans(&seg, fanOf, apexes);
        ASSERT_EQ(fans.fans.size(), 1u);
        if (!MayMeet(seg, hull)) continue;
        ++grazing;
        ASSERT_TRUE(FanMayMeet(fans.fans[0], hull)) << k;
    }
    EXPECT_GT(grazing, 15000);
}

// Reflections that hit nothing, as a floor patch sends them to the sky: loose segments
// without an end, from nearby origins in similar directions (with `strays`, one in 50 in
// any direction, as a curved mirror sends them).
RecordedBlock SkyReflections(std::mt19937_64 &rng, const Vec3 &patch, double patchSize, bool strays) {
    std::uniform_real_distribution<double> u(-1, 1);
    const Vec3 up = Normalised(Vec3{0.3 * u(rng), 1, 0.3 * u(rng)});
    RecordedBlock b;
    SampleRecorder recorder;
    StartRecordingRays(recorder);
    for (int i = 0; i < 200; ++i) {
        recorder.Begin(b.segments, b.fanOf, b.packed, b.apexes, nullptr, 0);
        const double eye[3] = {0.3, 2, -20};
        const Vec3 p = patch + Vec3{patchSize * u(rng), 0, patchSize * u(rng)};
        const Vec3 toP = Normalised(p - Vec3{eye[0], eye[1], eye[2]});
        const double d[3] = {toP.x, toP.y, toP.z};
        RecordRaySegment(eye, d, 10.0, kUnitNothing);
        const Vec3 r = strays && i % 50 == 0 ? Normalised(Vec3{u(rng), u(rng), u(rng)})
                                   : Normalised(up + Vec3{0.1 * u(rng), 0.1 * u(rng), 0.1 * u(rng)});
        const double po[3] = {p.x, p.y, p.z}, rd[3] = {r.x, r.y, r.z};
        RecordRaySegment(po, rd, 2e10, kUnitNothing);
    }
    StopRecordingRays();
    return b;
}

TEST(SegmentFans, UnboundedConeNeverMissesAHullItsRaysMeet) {
    std::mt19937_64 rng(37);
    std::uniform_real_distribution<double> pos(-15, 15), size(0.05, 3), patchSize(0.01, 4), unit(-1, 1);
    int checked = 0, rejects = 0, unboundedSegments = 0;
    for (int block = 0; block < 200; ++block) {
        const bool strays = block % 4 == 0;
        RecordedBlock b = SkyReflections(rng, Vec3{pos(rng), 0, pos(rng)}, patchSize(rng), strays);
        const BlockFans fans = BuildFans(b.segments.data(), b.fanOf, b.apexes);
        ASSERT_GE(fans.unbounded.reach, 0.0);
        for (int k = 0; k < 300; ++k) {
            Vec3 lo{pos(rng), pos(rng) * 0.5 + 5, pos(rng)};
            double edge = size(rng);
            if (k % 3 == 0) {  // a small box on one of the rays, far or near
                const Segment &s = b.segments[2 * std::size_t(rng() % 200) + 1];
                const double t = 1.0 + 60.0 * std::fabs(unit(rng));
                edge = 0.01;
                for (int a = 0; a < 3; ++a) lo[a] = s.origin[a] + t * s.direction[a] - 0.5 * edge;
            }
            Hull h = MakeHull(Box{lo, lo + Vec3{edge, edge, edge}});
            if (k % 2) {  // a slanted rod inside the box
                const Box &box = h.box;
                h = MakeHull(box, Capsule{box.lo + Vec3{0.05, 0.05, 0.05}, box.hi - Vec3{0.05, 0.05, 0.05}, 0.05});
            }
            const bool cone = FanMayMeet(fans.unbounded, h);
            rejects += !cone && !strays;
            for (std::size_t i = 0; i < b.segments.size(); ++i) {
                if (b.fanOf[i] != BlockFans::kLoose || InLooseBox(b.segments[i])) continue;
                unboundedSegments += k == 0;
                if (!MayMeet(b.segments[i], h)) continue;
                ++checked;
                ASSERT_TRUE(cone) << "block " << block << " hull " << k << " segment " << i;
            }
        }
    }
    EXPECT_EQ(unboundedSegments, 200 * 200);
    EXPECT_GT(checked, 2000);
    EXPECT_GT(rejects, 150 * 300 / 2);  // without strays the cone rejects most hulls
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
        recorder.Begin(a.segments, a.fanOf, a.packed, a.apexes, nullptr, 0);
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
        ValidateFanNumbers(a.fanOf, a.apexes);
        const BlockFans grown = GrowFans(fans, a.segments.data(), a.fanOf.data(), a.apexes, {{first, a.segments.size() - first}});
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
