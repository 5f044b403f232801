// Tests for segments and hulls: a stored (float) segment never misses a hull its traced
// (double) ray touches, checked against long-double references on random input.
#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "povrayfc/hull.h"
#include "povrayfc/segment.h"

using namespace povrayfc;

namespace {

const double kInf = std::numeric_limits<double>::infinity();
const double kNaN = std::numeric_limits<double>::quiet_NaN();

Segment Seg(Vec3 o, Vec3 d, double t) {
    const double od[3] = {o.x, o.y, o.z}, dd[3] = {d.x, d.y, d.z};
    Segment s;
    EXPECT_TRUE(MakeSegment(od, dd, t, s));
    return s;
}

// Exact slab test of the double ray against the closed box, in long double.
bool ExactMeetsBox(Vec3 o, Vec3 d, double tmax, const Box &b) {
    long double t0 = 0, t1 = tmax;
    for (int a = 0; a < 3; ++a) {
        if (d[a] == 0) {
            if (o[a] < b.lo[a] || o[a] > b.hi[a]) return false;
            continue;
        }
        long double ta = ((long double)b.lo[a] - o[a]) / d[a], tb = ((long double)b.hi[a] - o[a]) / d[a];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
        if (t0 > t1) return false;
    }
    return true;
}

// Distance between the double ray segment and the capsule axis in long double: ternary
// search along the ray (the distance to a segment is convex along a line).
long double ExactCapsuleDistance(Vec3 o, Vec3 d, double tmax, const Capsule &c) {
    auto point = [](Vec3 p, Vec3 v, long double t, long double out[3]) {
        for (int a = 0; a < 3; ++a) out[a] = p[a] + t * v[a];
    };
    const Vec3 axis = c.b - c.a;
    // Squared distance from the ray point at s to the axis segment, by exact projection.
    auto distToAxis = [&](long double s) {
        long double p[3], len2 = 0, dot = 0;
        point(o, d, s, p);
        for (int a = 0; a < 3; ++a) {
            len2 += (long double)axis[a] * axis[a];
            dot += (p[a] - c.a[a]) * axis[a];
        }
        long double u = len2 > 0 ? dot / len2 : 0;
        u = std::max((long double)0, std::min((long double)1, u));
        long double q[3], r = 0;
        point(c.a, axis, u, q);
        for (int a = 0; a < 3; ++a) r += (p[a] - q[a]) * (p[a] - q[a]);
        return r;
    };
    long double lo = 0, hi = tmax;
    for (int i = 0; i < 200; ++i) {
        long double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
        if (distToAxis(m1) < distToAxis(m2)) hi = m2; else lo = m1;
    }
    return std::sqrt(distToAxis((lo + hi) / 2));
}

TEST(Segment, RejectsWhatItCannotStoreConservatively) {
    const double o[3] = {0, 0, 0}, d[3] = {1, 0, 0};
    const double nanO[3] = {kNaN, 0, 0}, infD[3] = {kInf, 0, 0}, zero[3] = {0, 0, 0}, tiny[3] = {1e-30, 0, 0};
    Segment s;
    // Invariant: rays whose float copy could drift by more than the margin are refused.
    EXPECT_FALSE(MakeSegment(nanO, d, 1.0, s));
    // In any component (std::max keeps its first argument against a NaN second).
    const double nanLastO[3] = {1, 2, kNaN}, nanLastD[3] = {1, 0, kNaN};
    EXPECT_FALSE(MakeSegment(nanLastO, d, 1.0, s));
    EXPECT_FALSE(MakeSegment(o, nanLastD, 1.0, s));
    EXPECT_FALSE(MakeSegment(o, infD, 1.0, s));
    EXPECT_FALSE(MakeSegment(o, zero, 1.0, s));
    EXPECT_FALSE(MakeSegment(o, tiny, 1.0, s));
    EXPECT_FALSE(MakeSegment(o, d, kNaN, s));
    EXPECT_FALSE(MakeSegment(o, d, -1.0, s));
    ASSERT_TRUE(MakeSegment(o, d, kInf, s));
    EXPECT_EQ(s.length, std::numeric_limits<float>::infinity());
}

TEST(Segment, LengthIsRoundedUp) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(0.0, 100.0);
    const double o[3] = {0, 0, 0}, d[3] = {0, 1, 0};
    for (int i = 0; i < 10000; ++i) {
        const double t = u(rng);
        Segment s;
        ASSERT_TRUE(MakeSegment(o, d, t, s));
        // Invariant: the stored segment covers the whole traced one.
        EXPECT_GE(double(s.length), t);
    }
}

TEST(Hull, BoxHandPicked) {
    const Hull unit = MakeHull(Box{Vec3{0, 0, 0}, Vec3{1, 1, 1}});
    EXPECT_TRUE(MayMeet(Seg({-1, 0.5, 0.5}, {1, 0, 0}, 10), unit));
    EXPECT_FALSE(MayMeet(Seg({-1, 0.5, 0.5}, {1, 0, 0}, 0.5), unit));  // stops short
    EXPECT_TRUE(MayMeet(Seg({-1, 0.5, 0.5}, {1, 0, 0}, 1.0), unit));   // ends on the face
    EXPECT_FALSE(MayMeet(Seg({-1, 2, 0.5}, {1, 0, 0}, kInf), unit));   // passes beside
    EXPECT_TRUE(MayMeet(Seg({-1, 1, 1}, {1, 0, 0}, kInf), unit));      // grazes an edge
    EXPECT_FALSE(MayMeet(Seg({2, 0.5, 0.5}, {1, 0, 0}, kInf), unit));  // points away
    EXPECT_FALSE(MayMeet(Seg({0.5, 0.5, 0.5}, {1, 0, 0}, 1), Hull()));  // empty hull
    EXPECT_TRUE(MayMeet(Seg({0.5, 0.5, 0.5}, {0, 0, 1}, 0), unit));    // a point inside
}

TEST(Hull, RandomSegmentsNeverMissABoxTheyTouch) {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> pos(-50, 50), dir(-1, 1), len(0, 80), size(0.001, 10);
    int touching = 0, extra = 0;
    for (int i = 0; i < 200000; ++i) {
        Vec3 lo{pos(rng), pos(rng), pos(rng)};
        Box b{lo, lo + Vec3{size(rng), size(rng), size(rng)}};
        Vec3 o{pos(rng), pos(rng), pos(rng)};
        Vec3 target = (i % 2) ? Vec3{b.lo.x, pos(rng), b.hi.z} : 0.5 * (b.lo + b.hi);  // aim at faces/edges
        Vec3 d = target - o;
        if (i % 5 == 0) d = Vec3{dir(rng), dir(rng), dir(rng)};
        if (i % 7 == 0) d.y = 0;
        const double t = (i % 3 == 0) ? kInf : len(rng) / 40.0;
        Segment s;
        const double od[3] = {o.x, o.y, o.z}, dd[3] = {d.x, d.y, d.z};
        if (!MakeSegment(od, dd, t, s)) continue;
        const bool exact = ExactMeetsBox(o, d, t, b);
        const bool stored = MayMeet(s, MakeHull(b));
        // Invariant: never a miss; at most a hair of over-inclusion.
        if (exact) {
            ++touching;
            ASSERT_TRUE(stored) << i;
        } else {
            extra += stored;
        }
    }
    EXPECT_GT(touching, 50000);
    EXPECT_LT(extra, 200000 / 100);
}

TEST(Hull, RandomSegmentsNeverMissACapsuleTheyTouch) {
    std::mt19937_64 rng(13);
    std::uniform_real_distribution<double> pos(-20, 20), unit(-1, 1), rad(0.01, 3);
    int touching = 0, boxOnly = 0, capsuleRejects = 0;
    for (int i = 0; i < 20000; ++i) {
        Capsule c;
        c.a = Vec3{pos(rng), pos(rng), pos(rng)};
        c.b = (i % 4 == 0) ? c.a : c.a + Vec3{3 * unit(rng), 3 * unit(rng), 3 * unit(rng)};
        c.radius = rad(rng);
        Box box;
        box.Grow(c.a - Vec3{c.radius, c.radius, c.radius});
        box.Grow(c.b + Vec3{c.radius, c.radius, c.radius});
        box.Grow(c.a + Vec3{c.radius, c.radius, c.radius});
        box.Grow(c.b - Vec3{c.radius, c.radius, c.radius});
        Vec3 o{pos(rng), pos(rng), pos(rng)};
        // Aim close to the surface: through a point at about the radius from the axis.
        Vec3 onAxis = c.a + (0.5 + 0.5 * unit(rng)) * (c.b - c.a);
        Vec3 off{unit(rng), unit(rng), unit(rng)};
        const double offLen = std::sqrt(off.x * off.x + off.y * off.y + off.z * off.z);
        Vec3 target = onAxis + (c.radius * (1.0 + 0.02 * unit(rng)) / offLen) * off;
        Vec3 d = target - o;
        if (i % 9 == 0) d = (c.b - c.a);  // parallel to the axis
        const double t = (i % 3 == 0) ? kInf : 2.0 * (0.5 + 0.5 * unit(rng));
        Segment s;
        const double od[3] = {o.x, o.y, o.z}, dd[3] = {d.x, d.y, d.z};
        if (!MakeSegment(od, dd, t, s)) continue;
        const double tt = std::isinf(t) ? 1e3 : t;
        const bool exact = ExactCapsuleDistance(o, d, tt, c) <= c.radius * (1 - 1e-12) && ExactMeetsBox(o, d, tt, box);
        const Hull h = MakeHull(box, c);
        const bool stored = MayMeet(s, h);
        if (exact) {
            ++touching;
            // Invariant: a ray that reaches into the capsule is never missed.
            ASSERT_TRUE(stored) << i;
        }
        if (MayMeet(s, MakeHull(box)) && !stored) ++capsuleRejects;
        boxOnly += MayMeet(s, MakeHull(box));
    }
    EXPECT_GT(touching, 1000);
    // The capsule refines the box: some rays through the box miss the capsule.
    EXPECT_GT(capsuleRejects, 100);
    EXPECT_GT(boxOnly, touching);
}

// ClearanceWidened: the stored segment misses the box widened by the margin and the clearance
// (checked exactly, with half the margin left for the test's own rounding), is 0 whenever
// MeetsWidened says the segment may meet the box, and is often positive (it must be, for
// block_tracer.cpp to skip any test).
TEST(Hull, ClearanceIsAWideningTheSegmentStillMisses) {
    std::mt19937_64 rng(17);
    std::uniform_real_distribution<double> pos(-50, 50), dir(-1, 1), len(0, 80), size(0.001, 10);
    int cleared = 0, tried = 0;
    for (int i = 0; i < 200000; ++i) {
        Vec3 lo{pos(rng), pos(rng), pos(rng)};
        const Box b{lo, lo + Vec3{size(rng), size(rng), size(rng)}};
        const Vec3 o{pos(rng), pos(rng), pos(rng)};
        Vec3 d = (i % 2) ? 0.5 * (b.lo + b.hi) - o + 3.0 * Vec3{dir(rng), dir(rng), dir(rng)}
                         : Vec3{dir(rng), dir(rng), dir(rng)};
        if (i % 7 == 0) d.z = 0;
        const double t = (i % 3 == 0) ? kInf : len(rng) / 40.0;
        Segment s;
        const double od[3] = {o.x, o.y, o.z}, dd[3] = {d.x, d.y, d.z};
        if (!MakeSegment(od, dd, t, s)) continue;
        ++tried;
        const Vec3 centre = 0.5 * (b.lo + b.hi), e = b.Extent();
        const double m = 4.0 * SegmentMargin(s, centre, 0.5 * std::max({e.x, e.y, e.z}));
        const double cap = 20.0;
        const double c = ClearanceWidened(s, b, m, cap);
        ASSERT_GE(c, 0.0);
        ASSERT_LE(c, cap);
        if (MeetsWidened(s, b, m)) {
            ASSERT_EQ(c, 0.0) << i;
            continue;
        }
        if (c == 0.0) continue;
        ++cleared;
        const double w = 0.5 * m + c;
        const Box widened{b.lo - Vec3{w, w, w}, b.hi + Vec3{w, w, w}};
        const Vec3 so{s.origin[0], s.origin[1], s.origin[2]}, sd{s.direction[0], s.direction[1], s.direction[2]};
        ASSERT_FALSE(ExactMeetsBox(so, sd, s.length, widened)) << i << " clearance " << c;
    }
    EXPECT_GT(cleared, tried / 3);
}

TEST(Hull, ClearanceHandPicked) {
    const Box unit{Vec3{0, 0, 0}, Vec3{1, 1, 1}};
    // Passing 2 above the box along x: it may widen by 2 beyond the margin.
    const double c = ClearanceWidened(Seg({-5, 3, 0.5}, {1, 0, 0}, kInf), unit, 0.0, 10.0);
    EXPECT_NEAR(c, 2.0, 1e-6);
    EXPECT_EQ(ClearanceWidened(Seg({-5, 0.5, 0.5}, {1, 0, 0}, kInf), unit, 0.0, 10.0), 0.0);  // through it
    EXPECT_EQ(ClearanceWidened(Seg({-5, 30, 0.5}, {1, 0, 0}, kInf), unit, 0.0, 10.0), 10.0);  // capped
    // Diagonal past a corner: only a cross axis separates it.
    const double diagonal = ClearanceWidened(Seg({2, -1, 0.5}, {1, 1, 0}, kInf), unit, 0.0, 10.0);
    EXPECT_GT(diagonal, 0.0);
    EXPECT_LT(diagonal, 2.0);
}

// A ray through a point of a triangle (or within its thickness of it) is never missed by
// the hull's triangle, whatever the ray, the triangle's shape (slivers too) or the float
// rounding of the segment; and the triangle refines its box: rays through the box that
// pass beside the triangle are rejected.
TEST(Hull, RandomSegmentsNeverMissATriangleTheyTouch) {
    std::mt19937_64 rng(29);
    std::uniform_real_distribution<double> pos(-30, 30), unit(-1, 1), weight(0.0, 1.0);
    int touching = 0, besideRejected = 0, beside = 0;
    for (int i = 0; i < 40000; ++i) {
        Triangle tri;
        tri.a = Vec3{pos(rng), pos(rng), pos(rng)};
        tri.b = tri.a + Vec3{4 * unit(rng), 4 * unit(rng), 4 * unit(rng)};
        tri.c = (i % 7 == 0) ? tri.a + 0.5 * (tri.b - tri.a) + Vec3{1e-3 * unit(rng), 0, 0}  // a sliver
                             : tri.a + Vec3{4 * unit(rng), 4 * unit(rng), 4 * unit(rng)};
        tri.thickness = (i % 3 == 0) ? 0.0 : 1e-3 * weight(rng);
        Box box;
        const Vec3 th{tri.thickness, tri.thickness, tri.thickness};
        for (const Vec3 &v : {tri.a, tri.b, tri.c}) box.Grow(v - th).Grow(v + th);
        // Aim at a point of the triangle (barycentric weights at least 1e-3), or beside it
        // (one weight at most -0.05), perhaps lifted off its plane within its thickness.
        const bool inside = i % 2 == 0;
        const double w1 = 1e-3 + weight(rng), w2 = 1e-3 + weight(rng), w3 = 1e-3 + weight(rng);
        // One in four of the points inside lies a hair from an edge, where only the margin
        // for the segment's float rounding keeps the ray...
        const double alpha = !inside ? -0.05 - weight(rng) : (i % 8 == 0 ? 1e-9 : w1 / (w1 + w2 + w3));
        const double beta = (1 - alpha) * w2 / (w2 + w3), gamma = 1 - alpha - beta;
        Vec3 target = alpha * tri.a + beta * tri.b + gamma * tri.c;
        if (tri.thickness > 0 && inside) target = target + Vec3{0.5 * tri.thickness * unit(rng), 0, 0};
        // ... seen from afar, where the segment's rounding dwarfs the triangle's hair.
        const double far = i % 8 == 0 ? 300.0 : 1.0;
        const Vec3 o{far * pos(rng), far * pos(rng), far * pos(rng)};
        const Vec3 d = (i % 5 == 0) ? 1e-3 * (target - o) : target - o;
        const double reach = (i % 5 == 0) ? 1e3 : 1.0;
        const double t = (i % 4 == 0) ? kInf : reach * (1.0 + 1e-6 + weight(rng));
        Segment s;
        const double od[3] = {o.x, o.y, o.z}, dd[3] = {d.x, d.y, d.z};
        if (!MakeSegment(od, dd, t, s)) continue;
        const Hull h = MakeHull(box, tri);
        ASSERT_TRUE(h.hasTriangle);
        const bool stored = MayMeet(s, h);
        if (inside) {
            ++touching;
            ASSERT_TRUE(stored) << i;
        } else if (MayMeet(s, MakeHull(box))) {
            ++beside;
            besideRejected += !stored;
        }
    }
    EXPECT_GT(touching, 15000);
    EXPECT_GT(besideRejected, beside / 2);
}

TEST(Hull, TriangleHandPicked) {
    Triangle tri{Vec3{-1, 0, 0}, Vec3{1, 0, 0}, Vec3{0, 1, 0}, 0.0};
    Box box{Vec3{-1, 0, 0}, Vec3{1, 1, 0}};
    const Hull h = MakeHull(box, tri);
    ASSERT_TRUE(h.hasTriangle);
    // Straight through the middle, through a corner of the box beside the triangle, along
    // an edge, and stopping short of the triangle.
    EXPECT_TRUE(MayMeet(Seg(Vec3{0, 0.3, -5}, Vec3{0, 0, 1}, kInf), h));
    EXPECT_FALSE(MayMeet(Seg(Vec3{0.9, 0.9, -5}, Vec3{0, 0, 1}, kInf), h));
    EXPECT_TRUE(MayMeet(Seg(Vec3{0.5, 0.5, -5}, Vec3{0, 0, 1}, kInf), h));
    EXPECT_FALSE(MayMeet(Seg(Vec3{0, 0.3, -5}, Vec3{0, 0, 1}, 4.9), h));
    EXPECT_TRUE(MayMeet(Seg(Vec3{0, 0.3, -5}, Vec3{0, 0, 1}, 5.0), h));
    // In its plane, beside it and across it.
    EXPECT_FALSE(MayMeet(Seg(Vec3{0.6, 1.1, 0}, Vec3{1, -1, 0}, kInf), h));
    EXPECT_TRUE(MayMeet(Seg(Vec3{-3, 0.2, 0}, Vec3{1, 0, 0}, kInf), h));
    // Thickness: a ray passing just above the plane meets a thick triangle only.
    EXPECT_FALSE(MayMeet(Seg(Vec3{-3, 0.2, 0.01}, Vec3{1, 0, 0}, kInf), h));
    Triangle thick = tri;
    thick.thickness = 0.02;
    Box thickBox = box;
    thickBox.lo.z = -0.02, thickBox.hi.z = 0.02;
    EXPECT_TRUE(MayMeet(Seg(Vec3{-3, 0.2, 0.01}, Vec3{1, 0, 0}, kInf), MakeHull(thickBox, thick)));
}

}  // namespace
