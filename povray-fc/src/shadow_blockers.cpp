// Shadow blockers: whether an opaque ball or box provably crosses a stored shadow test's way.
#include "povrayfc/shadow_blockers.h"

#include <algorithm>
#include <cmath>

#include "povrayfc/hull.h"

namespace povrayfc {

namespace {

// The depth each way from `centre`'s closest approach at which the ray (origin o, direction
// d, |d|^2 = dd) is `radius` from the centre; negative when it never comes that close.
double HalfChord(double distanceSquared, double radius, double dd) {
    const double h = radius * radius - distanceSquared;
    return h < 0.0 ? -1.0 : std::sqrt(h / dd);
}

}  // namespace

bool BallDarkens(const Segment &s, const Ball &ball) {
    const Vec3 o{s.origin[0], s.origin[1], s.origin[2]};
    const Vec3 d{s.direction[0], s.direction[1], s.direction[2]};
    const double dd = Dot(d, d);
    if (!(dd > 0.0) || !(ball.radius > 0.0) || !std::isfinite(s.length)) return false;
    // The traced ray lies within m of the stored one near the ball (twice the rounding
    // margin); g covers the rounding of this test and of POV-Ray's root finding, far
    // below m.
    const double m = 2.0 * SegmentMargin(s, ball.centre, ball.radius);
    const double scale = std::fabs(o.x) + std::fabs(o.y) + std::fabs(o.z) + std::fabs(ball.centre.x) +
                         std::fabs(ball.centre.y) + std::fabs(ball.centre.z) + ball.radius + double(s.length);
    const double g = 1e-9 * scale;
    const Vec3 oc = ball.centre - o;
    const double along = Dot(oc, d) / dd;  // depth of the closest approach
    const Vec3 closest = o + along * d;
    const Vec3 off = ball.centre - closest;
    const double distanceSquared = Dot(off, off);
    // Through the ball at depth: inside the ball shrunk by m + g, with a chord that the
    // loop cannot step over from a surface just in front (twice its tolerance).
    // POV-Ray's tolerances are depths along its unit direction; this segment's direction
    // need not be unit (segment_packing.h), so they are divided by its length.
    const double unit = std::sqrt(dd);
    const double inner = HalfChord(distanceSquared, ball.radius - m - g, dd);
    if (inner < 2.0 * kShadowTolerance / unit) return false;
    // The whole ball, grown by m + g, between the tolerances: the traced ray enters and
    // leaves the real ball there, so the loop meets one of its surfaces (length was
    // rounded up when stored, so the test's reach is a hair shorter).
    const double outer = HalfChord(distanceSquared, ball.radius + m + g, dd);
    const double reach = double(s.length) * (1.0 - 0x1p-20);
    const double tolerance = (kShadowTolerance + g) / unit;
    return along - outer > tolerance && along + outer < reach - tolerance;
}

bool BoxDarkens(const Segment &s, const Box &box) {
    const Vec3 o{s.origin[0], s.origin[1], s.origin[2]};
    const Vec3 d{s.direction[0], s.direction[1], s.direction[2]};
    const double dd = Dot(d, d);
    if (!(dd > 0.0) || box.Empty() || !box.IsFinite() || !std::isfinite(s.length)) return false;
    const Vec3 centre = 0.5 * (box.lo + box.hi);
    const Vec3 half = 0.5 * (box.hi - box.lo);
    const double radius = std::max(half.x, std::max(half.y, half.z));
    // m and g as for a ball (BallDarkens): the traced ray's point at each depth lies within
    // m of the stored one's, so where the stored ray is inside the box shrunk by m + g the
    // traced one is inside the box, and where it is outside the box grown by m + g, so is
    // the traced one; the box being convex, the traced ray's chord lies between the two.
    const double m = 2.0 * SegmentMargin(s, centre, radius);
    const double scale = std::fabs(o.x) + std::fabs(o.y) + std::fabs(o.z) + std::fabs(centre.x) +
                         std::fabs(centre.y) + std::fabs(centre.z) + radius + double(s.length);
    const double e = m + 1e-9 * scale;
    const double reach = double(s.length) * (1.0 - 0x1p-20);
    // POV-Ray's box takes a ray as parallel to a slab when that component of its unit
    // direction is within 1e-10 of 0, and then bounds it there only by where it starts. That
    // moves no entry this test accepts. From inside the slab only the ray's way out moves
    // (farther), and its entry is the other slabs' as before. From outside, POV-Ray finds
    // nothing, and the stored ray (whose component is within 2^-21 of the largest of the
    // traced one's) reaches the slab shrunk by e only beyond 2e6 e from its origin, while e
    // is at least 2^-18 of the farthest a point of the box lies from there: the chord below
    // is empty.
    double innerNear = 0.0, innerFar = reach, outerNear = -HUGE_VAL, outerFar = HUGE_VAL;
    for (int axis = 0; axis < 3; ++axis) {
        const double lo = box.lo[axis], hi = box.hi[axis], oi = o[axis], di = d[axis];
        if (!(hi - e > lo + e)) return false;  // no inside left once shrunk
        if (di == 0.0) {
            if (!(oi > lo + e && oi < hi - e)) return false;
            continue;
        }
        double a = (lo + e - oi) / di, b = (hi - e - oi) / di;
        if (a > b) std::swap(a, b);
        innerNear = std::max(innerNear, a);
        innerFar = std::min(innerFar, b);
        a = (lo - e - oi) / di;
        b = (hi + e - oi) / di;
        if (a > b) std::swap(a, b);
        outerNear = std::max(outerNear, a);
        outerFar = std::min(outerFar, b);
    }
    // Through the box at depth, with a chord the loop cannot step over from a surface just
    // in front (twice its tolerance); the whole box, grown, between the tolerances. As for a
    // ball, the tolerances are depths along a unit direction.
    const double unit = std::sqrt(dd);
    const double tolerance = (kShadowTolerance + 1e-9 * scale) / unit;
    return innerFar - innerNear >= 2.0 * kShadowTolerance / unit && outerNear > tolerance &&
           outerFar < reach - tolerance;
}

const Blocker *DarkeningBlocker(const Segment &s, const std::vector<Blocker> &blockers) {
    for (const Blocker &b : blockers)
        if (b.isBox ? BoxDarkens(s, b.box) : BallDarkens(s, b.ball)) return &b;
    return nullptr;
}

}  // namespace povrayfc
