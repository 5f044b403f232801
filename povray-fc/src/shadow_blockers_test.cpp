// Shadow blockers: a ball darkens a stored shadow test only when the traced ray, wherever
// the stored one's rounding puts it, enters and leaves the ball within the depths the
// shadow loop accepts.
#include "povrayfc/shadow_blockers.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "povrayfc/hull.h"
#include "povrayfc/ray_recording.h"

namespace povrayfc {
namespace {

Segment ShadowTest(Vec3 o, Vec3 d, double reach) {
    const double origin[3] = {o.x, o.y, o.z}, direction[3] = {d.x, d.y, d.z};
    Segment s;
    EXPECT_TRUE(MakeSegment(origin, direction, reach, s));
    s.unit = 7 | Segment::kOpaqueBlocker;
    return s;
}

const Vec3 kUp{0, 1, 0};

TEST(ShadowBlockers, ABallSquarelyOnTheWayDarkensIt) {
    EXPECT_TRUE(BallDarkens(ShadowTest({0, 0, 0}, kUp, 50), Ball{{0.5, 20, 0}, 5}));
    const std::vector<Blocker> two = {Blocker::OfBall(Ball{{30, 20, 0}, 1}, 4), Blocker::OfBall(Ball{{0, 10, 0}, 2}, 9)};
    const Blocker *found = DarkeningBlocker(ShadowTest({0, 0, 0}, kUp, 50), two);
    ASSERT_NE(found, nullptr);
    EXPECT_EQ(found->unit, 9u);
    EXPECT_EQ(DarkeningBlocker(ShadowTest({0, 0, 0}, kUp, 50), {two[0]}), nullptr);
    EXPECT_EQ(DarkeningBlocker(ShadowTest({0, 0, 0}, kUp, 50), {}), nullptr);
}

TEST(ShadowBlockers, AGrazedBallDoesNot) {
    // The ray passes inside the ball by less than the rounding could move it.
    const Segment s = ShadowTest({0, 0, 0}, kUp, 50);
    const double m = 2.0 * SegmentMargin(s, Vec3{5, 20, 0}, 5);
    EXPECT_FALSE(BallDarkens(s, Ball{{5 - 0.5 * m, 20, 0}, 5}));
    EXPECT_TRUE(BallDarkens(s, Ball{{4.9, 20, 0}, 5}));
}

TEST(ShadowBlockers, TheWholeBallMustLieBetweenTheTolerances) {
    const Segment s = ShadowTest({0, 0, 0}, kUp, 50);
    // The origin inside the ball: the loop may see only its far side, or nothing of it.
    EXPECT_FALSE(BallDarkens(s, Ball{{0, 1, 0}, 2}));
    // Its near side within the tolerance of the origin.
    EXPECT_FALSE(BallDarkens(s, Ball{{0, 2.0005, 0}, 2}));
    EXPECT_TRUE(BallDarkens(s, Ball{{0, 2.01, 0}, 2}));
    // Its far side past the light, or within the tolerance of it.
    EXPECT_FALSE(BallDarkens(s, Ball{{0, 49, 0}, 2}));
    EXPECT_FALSE(BallDarkens(s, Ball{{0, 47.9995, 0}, 2}));
    EXPECT_TRUE(BallDarkens(s, Ball{{0, 47.99, 0}, 2}));
    // Behind the origin.
    EXPECT_FALSE(BallDarkens(s, Ball{{0, -10, 0}, 2}));
}

TEST(ShadowBlockers, TheTolerancesAreDepthsWhateverTheDirectionsLength) {
    // A packed segment's direction need not be unit (segment_packing.h): here half, so
    // its parameter runs twice the depth. The ball's near side lies 0.0007 from the
    // origin, inside the loop's tolerance of 0.001 as a depth (0.0014 as a parameter).
    const Segment half = ShadowTest({0, 0, 0}, {0, 0.5, 0}, 100);
    EXPECT_FALSE(BallDarkens(half, Ball{{0, 2.0007, 0}, 2}));
    EXPECT_TRUE(BallDarkens(half, Ball{{0, 2.01, 0}, 2}));
    // Its far side 0.0007 before the light.
    EXPECT_FALSE(BallDarkens(half, Ball{{0, 47.9993, 0}, 2}));
    EXPECT_TRUE(BallDarkens(half, Ball{{0, 47.99, 0}, 2}));
}

TEST(ShadowBlockers, AChordTheLoopCouldStepOverDoesNotDarken) {
    // A loop restarting at a transparent surface just in front of the ball skips surfaces
    // within its tolerance: a chord of less than twice that proves nothing.
    const Segment s = ShadowTest({0, 0, 0}, kUp, 50);
    EXPECT_FALSE(BallDarkens(s, Ball{{0, 10, 0}, 0.0015}));
    EXPECT_TRUE(BallDarkens(s, Ball{{0, 10, 0}, 0.01}));
}

TEST(ShadowBlockers, UnplaceableInputNeverDarkens) {
    Segment s = ShadowTest({0, 0, 0}, kUp, 50);
    EXPECT_FALSE(BallDarkens(s, Ball{{0, 20, 0}, 0}));
    EXPECT_FALSE(BallDarkens(s, Ball{{0, 20, 0}, std::nan("")}));
    EXPECT_FALSE(BallDarkens(s, Ball{{std::nan(""), 20, 0}, 5}));
    s.length = std::numeric_limits<float>::infinity();
    EXPECT_FALSE(BallDarkens(s, Ball{{0, 20, 0}, 5}));
}

Vec3 Unit(const Vec3 &v) { return (1.0 / std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z)) * v; }

// Invariant: whenever a ball darkens a stored test, every ray the stored segment may stand
// for (its double-precision original, moved within the rounding) enters and leaves the
// ball at depths the shadow loop accepts, with a chord it cannot step over. The balls are
// placed at the edges of what the rule accepts: grazing the ray, or with a side near the
// tolerance at the origin or at the light, each by 10^-1 to 10^-13 of the scene's size.
TEST(ShadowBlockers, EveryRayTheSegmentStandsForCrossesTheBallWithinTheTolerances) {
    std::mt19937_64 rng(20261206);
    std::uniform_real_distribution<double> u(-1.0, 1.0), exponent(1.0, 13.0);
    int darkened = 0;
    for (int trial = 0; trial < 300000; ++trial) {
        const double scale = std::pow(10.0, 2.0 * u(rng));
        const Vec3 o{scale * 40 * u(rng), scale * 40 * u(rng), scale * 40 * u(rng)};
        const Vec3 d = Unit(Vec3{u(rng), u(rng), u(rng)} + Vec3{0, 0, 1e-3});
        const Vec3 side = Unit(Cross(d, Vec3{u(rng), u(rng), u(rng)} + Vec3{1e-3, 0, 0}));
        const double reach = scale * (1 + 30 * (u(rng) + 1));
        const double radius = scale * 2 * (u(rng) + 1.001);
        const double near = std::pow(10.0, -exponent(rng));
        double off = radius * (u(rng) + 1) / 2, at = reach / 2;
        switch (trial % 3) {
            case 0: off = radius * (1 - near); break;                                  // grazing
            case 1: at = kShadowTolerance + std::sqrt(radius * radius - off * off) + near * scale; break;
            default: at = reach - kShadowTolerance - std::sqrt(radius * radius - off * off) - near * scale; break;
        }
        const Vec3 centre = o + at * d + off * side;
        const double origin[3] = {o.x, o.y, o.z}, direction[3] = {d.x, d.y, d.z};
        Segment s;
        if (!MakeSegment(origin, direction, reach, s)) continue;
        s.unit = Segment::kOpaqueBlocker;
        const Ball ball{centre, radius};
        if (!BallDarkens(s, ball)) continue;
        ++darkened;
        // The traced ray: the original, then moved by up to half the rounding margin (single
        // precision moves it by a sixteenth).
        for (int k = 0; k < 4; ++k) {
            const double wiggle = k == 0 ? 0.0 : 0.5 * SegmentMargin(s, centre, radius);
            const Vec3 to = o + Vec3{wiggle * u(rng), wiggle * u(rng), wiggle * u(rng)};
            const Vec3 oc = to - centre;
            const double b = oc.x * d.x + oc.y * d.y + oc.z * d.z;
            const double c = oc.x * oc.x + oc.y * oc.y + oc.z * oc.z - radius * radius;
            const double disc = b * b - c;
            ASSERT_GT(disc, 0.0) << trial;
            const double t1 = -b - std::sqrt(disc), t2 = -b + std::sqrt(disc);
            ASSERT_GT(t1, kShadowTolerance) << trial;
            ASSERT_LT(t2, reach - kShadowTolerance) << trial;
            ASSERT_GT(t2 - t1, 2 * kShadowTolerance) << trial;
        }
    }
    EXPECT_GT(darkened, 50000);  // the invariant was put to the test
}

TEST(ShadowBlockers, ABoxSquarelyOnTheWayDarkensIt) {
    const Segment s = ShadowTest({0, 0, 0}, Unit(Vec3{0.2, 1, 0.1}), 50);
    EXPECT_TRUE(BoxDarkens(s, Box{{-2, 18, -2}, {8, 22, 8}}));
    const std::vector<Blocker> two = {Blocker::OfBall(Ball{{30, 20, 0}, 1}, 4),
                                      Blocker::OfBox(Box{{-2, 18, -2}, {8, 22, 8}}, 9)};
    const Blocker *found = DarkeningBlocker(s, two);
    ASSERT_NE(found, nullptr);
    EXPECT_EQ(found->unit, 9u);
    // Beside the way, behind the origin, past the light, flat: nothing.
    EXPECT_FALSE(BoxDarkens(s, Box{{20, 18, -2}, {28, 22, 8}}));
    EXPECT_FALSE(BoxDarkens(s, Box{{-8, -22, -8}, {8, -18, 8}}));
    EXPECT_FALSE(BoxDarkens(s, Box{{-20, 60, -20}, {20, 70, 20}}));
    EXPECT_FALSE(BoxDarkens(s, Box{{-20, 20, -20}, {20, 20, 20}}));
    EXPECT_FALSE(BoxDarkens(s, Box{}));
}

TEST(ShadowBlockers, TheWholeBoxMustLieBetweenTheTolerancesWithAChordAtDepth) {
    const Segment s = ShadowTest({0, 0, 0}, kUp, 50);
    // The origin inside it, or its near side within the tolerance of the origin.
    EXPECT_FALSE(BoxDarkens(s, Box{{-1, -1, -1}, {1, 1, 1}}));
    EXPECT_FALSE(BoxDarkens(s, Box{{-1, 0.0005, -1}, {1, 2, 1}}));
    EXPECT_TRUE(BoxDarkens(s, Box{{-1, 0.01, -1}, {1, 2, 1}}));
    // Its far side past the light or within the tolerance of it.
    EXPECT_FALSE(BoxDarkens(s, Box{{-1, 48, -1}, {1, 51, 1}}));
    EXPECT_FALSE(BoxDarkens(s, Box{{-1, 48, -1}, {1, 49.9995, 1}}));
    EXPECT_TRUE(BoxDarkens(s, Box{{-1, 48, -1}, {1, 49.99, 1}}));
    // A chord the loop could step over.
    EXPECT_FALSE(BoxDarkens(s, Box{{-1, 10, -1}, {1, 10.0015, 1}}));
    EXPECT_TRUE(BoxDarkens(s, Box{{-1, 10, -1}, {1, 10.01, 1}}));
    // Grazed: the ray runs along a face, within the rounding of it.
    const double m = 2.0 * SegmentMargin(s, Vec3{0, 20, 0}, 5);
    EXPECT_FALSE(BoxDarkens(s, Box{{-0.5 * m, 15, -5}, {5, 25, 5}}));
    EXPECT_TRUE(BoxDarkens(s, Box{{-0.1, 15, -5}, {5, 25, 5}}));
}

// POV-Ray's own box test (box.cpp, Box::Intersect) of a ray against a box without a
// transformation: the depths it enters and leaves at, or false.
bool PovRayBox(const Vec3 &p, const Vec3 &d, const Box &box, double &tmin, double &tmax) {
    const double kEpsilon = 1.0e-10;
    tmin = 0.0;
    tmax = 1.0e10;
    for (int axis = 0; axis < 3; ++axis) {
        const double lo = box.lo[axis], hi = box.hi[axis];
        if (d[axis] < -kEpsilon || d[axis] > kEpsilon) {
            double t1 = (lo - p[axis]) / d[axis], t2 = (hi - p[axis]) / d[axis];
            if (t1 > t2) std::swap(t1, t2);
            if (t2 < tmin || t1 > tmax) return false;
            tmin = std::max(tmin, t1);
            tmax = std::min(tmax, t2);
        } else if (p[axis] < lo || p[axis] > hi) {
            return false;
        }
    }
    return tmax >= 1.0e-6;
}

// Invariant: whenever a box darkens a stored test, every ray the stored segment may stand
// for meets it, by POV-Ray's own test, entering and leaving within the depths the shadow
// loop accepts, with a chord it cannot step over. The boxes graze the ray, lie near a
// tolerance, or have a face nearly parallel to it, each by 10^-1 to 10^-13 of the scene.
TEST(ShadowBlockers, EveryRayTheSegmentStandsForCrossesTheBoxWithinTheTolerances) {
    std::mt19937_64 rng(20261207);
    std::uniform_real_distribution<double> u(-1.0, 1.0), exponent(1.0, 13.0);
    int darkened = 0;
    for (int trial = 0; trial < 300000; ++trial) {
        const double scale = std::pow(10.0, 2.0 * u(rng));
        const double near = std::pow(10.0, -exponent(rng));
        const Vec3 o{scale * 40 * u(rng), scale * 40 * u(rng), scale * 40 * u(rng)};
        Vec3 d = Unit(Vec3{u(rng), u(rng), u(rng)} + Vec3{0, 0, 1e-3});
        if (trial % 4 == 3) d[trial % 3] = near * u(rng);  // nearly parallel to a slab
        d = Unit(d);
        const double reach = scale * (1 + 30 * (u(rng) + 1));
        const double at = reach * (u(rng) + 1) / 2;
        const Vec3 half{scale * 2 * (u(rng) + 1.001), scale * 2 * (u(rng) + 1.001), scale * 2 * (u(rng) + 1.001)};
        Vec3 centre = o + at * d + Vec3{half.x * u(rng), half.y * u(rng), half.z * u(rng)};
        Box box{centre - half, centre + half};
        switch (trial % 4) {
            case 0: {  // grazing: a face through a point of the ray
                const int axis = trial % 3;
                box.lo[axis] = (o + at * d)[axis] - near * scale;
                break;
            }
            case 1:  // the near side at the tolerance from the origin
                box.lo = o + (kShadowTolerance + near * scale) * d - Vec3{0, 0, 0} - 0.5 * half;
                box.hi = box.lo + half;
                break;
            case 2:  // the far side at the tolerance before the light
                box.hi = o + (reach - kShadowTolerance - near * scale) * d + 0.5 * half;
                box.lo = box.hi - half;
                break;
            default: break;
        }
        const double origin[3] = {o.x, o.y, o.z}, direction[3] = {d.x, d.y, d.z};
        Segment s;
        if (!MakeSegment(origin, direction, reach, s)) continue;
        s.unit = Segment::kOpaqueBlocker;
        if (!BoxDarkens(s, box)) continue;
        ++darkened;
        const Vec3 c = 0.5 * (box.lo + box.hi);
        const double radius = std::max(half.x, std::max(half.y, half.z));
        for (int k = 0; k < 4; ++k) {
            const double wiggle = k == 0 ? 0.0 : 0.5 * SegmentMargin(s, c, radius);
            const Vec3 to = o + Vec3{wiggle * u(rng), wiggle * u(rng), wiggle * u(rng)};
            double t1, t2;
            ASSERT_TRUE(PovRayBox(to, d, box, t1, t2)) << trial;
            ASSERT_GT(t1, kShadowTolerance) << trial;
            ASSERT_LT(t2, reach - kShadowTolerance) << trial;
            ASSERT_GT(t2 - t1, 2 * kShadowTolerance) << trial;
        }
    }
    EXPECT_GT(darkened, 30000);  // the invariant was put to the test
}

// A shadow test an opaque blocker answered is one segment, whatever transparent objects it
// passed on its way there: from the loop's last origin, over the depth it looked up to.
TEST(ShadowBlockers, AnOpaqueBlockersTestKeepsItsPiecesPastGlassAndOneSegmentOverTheRest) {
    std::vector<Segment> segments;
    std::vector<std::uint8_t> fanOf;
    std::vector<std::uint8_t> packed;
    FanApexes apexes;
    const std::uint32_t ids[3] = {10, 11, 12};
    SampleRecorder recorder;
    StartRecordingRays(recorder);
    recorder.Begin(segments, fanOf, packed, apexes, ids, 3);
    double origin[3] = {0, 0, 0};
    const double up[3] = {0, 1, 0};
    RecordRaySegment(origin, up, 3.0, 0);
    {
        double depth = 50.0;
        ShadowSegmentRecord shadow(origin, up, depth);
        shadow.ProjectedDepth(4.0);
        shadow.PassedAt(10.0, 1);  // the loop moves on past a pane of glass
        origin[1] = 10.0;
        depth -= 10.0;
        shadow.BlockedAt(5.0, 2, true);
    }
    StopRecordingRays();
    // Where the loop met the blocker from hangs on the glass it went on from: that piece stays.
    ASSERT_EQ(recorder.Count(), 3u);
    const Segment &pane = segments[1];
    EXPECT_EQ(pane.unit, 11u);
    EXPECT_TRUE(pane.HullTested());
    EXPECT_NEAR(pane.length, 10.0, 1e-4);
    const Segment &blocked = segments[2];
    EXPECT_EQ(blocked.unit, 12u | Segment::kOpaqueBlocker);
    EXPECT_FALSE(blocked.HullTested());
    EXPECT_NEAR(blocked.origin[1], 10.0, 1e-4);  // the pane's end, packed as such
    EXPECT_NEAR(blocked.length, 36.0, 1e-4);
    EXPECT_EQ(fanOf.size(), segments.size());
}

TEST(ShadowBlockers, AnyOtherBlockerKeepsItsPiecesAndWhereItStopped) {
    std::vector<Segment> segments;
    std::vector<std::uint8_t> fanOf;
    std::vector<std::uint8_t> packed;
    FanApexes apexes;
    const std::uint32_t ids[3] = {10, 11, 12};
    SampleRecorder recorder;
    StartRecordingRays(recorder);
    recorder.Begin(segments, fanOf, packed, apexes, ids, 3);
    double origin[3] = {0, 0, 0};
    const double up[3] = {0, 1, 0};
    {
        double depth = 50.0;
        ShadowSegmentRecord shadow(origin, up, depth);
        shadow.PassedAt(10.0, 1);
        origin[1] = 10.0;
        depth -= 10.0;
        shadow.BlockedAt(5.0, 2, false);  // dark by its texture: its colour matters
    }
    StopRecordingRays();
    ASSERT_EQ(recorder.Count(), 2u);
    EXPECT_EQ(segments[0].unit, 11u);
    EXPECT_EQ(segments[1].unit, 12u);
    EXPECT_TRUE(segments[1].HullTested());
    EXPECT_NEAR(segments[1].length, 5.0, 1e-5);
}

// A recorder that writes in full keeps its segments unwritten until the sample closes,
// drops a shadow test's moot pieces all the same, and then writes exactly the segments it
// kept, as MakeSegment rounds the traced rays.
TEST(ShadowBlockers, ARecorderWritingInFullWritesTheSegmentsItKeptWhenTheSampleCloses) {
    std::vector<Segment> segments;
    std::vector<std::uint8_t> fanOf;
    std::vector<std::uint8_t> packed = {0xab};  // an earlier sample's byte stays
    FanApexes apexes;
    const std::uint32_t ids[3] = {10, 11, 12};
    SampleRecorder recorder;
    StartRecordingRays(recorder);
    recorder.Begin(segments, fanOf, packed, apexes, ids, 3, false);
    double origin[3] = {0.1, 0.2, 0.3};
    const double up[3] = {0, 1, 0}, slant[3] = {0.3, -0.2, 0.9};
    RecordRaySegment(origin, slant, 3.0, 0);
    {
        double depth = 50.0;
        ShadowSegmentRecord shadow(origin, up, depth);
        RecordRaySegment(origin, slant, 7.0, 1);  // traced within the test: moot once it is blocked
        shadow.BlockedAt(5.0, 2, true);
    }
    {
        double depth = 20.0;
        ShadowSegmentRecord shadow(origin, slant, depth);  // reaches its light
    }
    StopRecordingRays();
    ASSERT_EQ(recorder.Count(), 3u);
    EXPECT_EQ(packed.size(), 1u) << "nothing is written before the sample closes";
    recorder.Close();

    Segment expected[3];
    ASSERT_TRUE(MakeSegment(origin, slant, 3.0, expected[0]));
    expected[0].unit = 10;
    ASSERT_TRUE(MakeSegment(origin, up, 50.0, expected[1]));
    expected[1].unit = 12 | Segment::kOpaqueBlocker;
    ASSERT_TRUE(MakeSegment(origin, slant, 20.0, expected[2]));
    expected[2].unit = Segment::kNoUnit;
    EXPECT_EQ(packed.size(), 1u + 34 + 34 + 30);
    EXPECT_EQ(packed[0], 0xab);
    Segment read[3];
    std::uint8_t fans[3];
    ASSERT_TRUE(UnpackSample(packed.data() + 1, 3, apexes, read, fans));
    for (int i = 0; i < 3; ++i) {
        EXPECT_EQ(std::memcmp(&read[i], &expected[i], sizeof(Segment)), 0) << "segment " << i;
        EXPECT_EQ(std::memcmp(&segments[i], &expected[i], sizeof(Segment)), 0) << "segment " << i;
        EXPECT_EQ(fans[i], fanOf[i]);
    }

    // A ray that cannot be stored makes the next sample depend on everything.
    recorder.Begin(segments, fanOf, packed, apexes, ids, 3, false);
    StartRecordingRays(recorder);
    const double none[3] = {0, 0, 0};
    RecordRaySegment(origin, none, 1.0, 0);
    StopRecordingRays();
    EXPECT_TRUE(recorder.Everything());
}

}  // namespace
}  // namespace povrayfc
