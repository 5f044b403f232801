// Shadow blockers: whether an opaque ball provably crosses a stored shadow test's way.
#include "povrayfc/shadow_blockers.h"

#include <algorithm>
#include <cmath>

#include "povrayfc/hull.h"

namespace povrayfc {

namespace {

double Dot(const Vec3 &a, const Vec3 &b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

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

const Blocker *DarkeningBlocker(const Segment &s, const std::vector<Blocker> &blockers) {
    for (const Blocker &b : blockers)
        if (BallDarkens(s, b.ball)) return &b;
    return nullptr;
}

}  // namespace povrayfc
