// Hull: a region of space whose contents changed between two frames, and the conservative
// test of a stored ray segment against it.
#ifndef POVRAYFC_HULL_H
#define POVRAYFC_HULL_H

#include <algorithm>
#include <cmath>

#include "povrayfc/geometry.h"
#include "povrayfc/segment.h"

namespace povrayfc {

// A changed region: always a box, optionally refined by a capsule (spheres, cylinders and
// cones, whose boxes are loose when slanted). A point can only have changed if it lies in
// the box and, when there is one, in the capsule.
struct Hull {
    Box box;
    bool hasCapsule = false;
    Capsule capsule;
};

// A hull around `box` (and `capsule`), widened by a relative hair so that single-precision
// bounding boxes of POV-Ray's objects (rounded to nearest, not outward) still contain the
// object. Throws std::invalid_argument for NaN; an empty box gives an empty hull.
Hull MakeHull(const Box &box);
Hull MakeHull(const Box &box, const Capsule &capsule);

// How far from a stored segment the ray it stands for may lie, near a target of centre c
// and half extent h (max norm): the float rounding of origin, direction and length moves
// the ray by at most 2^-23 of (|origin| + the distance to the far side of the target);
// the margin is 16 times that.
inline double SegmentMargin(const Segment &s, const Vec3 &c, double h) {
    const double x = s.origin[0], y = s.origin[1], z = s.origin[2];
    const double o = std::max(std::fabs(x), std::max(std::fabs(y), std::fabs(z)));
    const double oc = std::max(std::fabs(x - c.x), std::max(std::fabs(y - c.y), std::fabs(z - c.z)));
    return 0x1p-19 * (o + oc + h) + 1e-30;
}

// Cheap rejection before a slab test: true when the segment lies entirely beyond one
// face of `box` widened by `margin` (both of its ends past it, an unbounded ray moving
// away or parallel). No division.
inline bool BeyondOneFace(const Segment &s, const Box &box, double margin) {
    const double length = s.length;
    for (int a = 0; a < 3; ++a) {
        const double o = s.origin[a], d = s.direction[a];
        const double e = d == 0.0 ? o : o + length * d;  // +-inf for an unbounded ray
        const double lo = box.lo[a] - margin, hi = box.hi[a] + margin;
        if ((o < lo && e < lo) || (o > hi && e > hi)) return true;
    }
    return false;
}

// True when the ray a segment stands for may pass through the closed box (a slab test
// against the box widened by SegmentMargin). Never false for a ray that touches it.
bool MayMeet(const Segment &s, const Box &box);
// The separating-axis test against `box` widened by `margin` (finite boxes only): false
// only when the segment provably misses it; a NaN anywhere gives true.
inline bool MeetsWidened(const Segment &s, const Box &box, double m) {
    // The box's three axes and their cross products with the segment, all multiplications:
    // a slab test's three divisions cost more than the rest of the test together, and
    // this runs for every stored segment near a change every frame. Every length is
    // scaled by k, the direction's largest component (> 0, see MakeSegment), which spares
    // the division that bounds an unbounded ray: the comparisons scale alike, and the
    // rounding this moves is ~1e-16 of the magnitudes, far inside m.
    const double ox = s.origin[0], oy = s.origin[1], oz = s.origin[2];
    const double dx = s.direction[0], dy = s.direction[1], dz = s.direction[2];
    const double cx = 0.5 * (box.lo.x + box.hi.x), cy = 0.5 * (box.lo.y + box.hi.y), cz = 0.5 * (box.lo.z + box.hi.z);
    const double ex = 0.5 * (box.hi.x - box.lo.x) + m, ey = 0.5 * (box.hi.y - box.lo.y) + m,
                 ez = 0.5 * (box.hi.z - box.lo.z) + m;
    const double ocx = ox - cx, ocy = oy - cy, ocz = oz - cz;
    const double k = std::max(std::fabs(dx), std::max(std::fabs(dy), std::fabs(dz)));
    // Beyond `reach` / k along the ray every point is farther from c than any point of the
    // box (|v|_2 <= |v|_1), which bounds an unbounded ray.
    const double reach = std::fabs(ocx) + std::fabs(ocy) + std::fabs(ocz) + ex + ey + ez;
    const double half = 0.5 * std::min(double(s.length) * k, reach);
    const double hx = half * dx, hy = half * dy, hz = half * dz;  // k times half the segment
    const double mx = k * ocx + hx, my = k * ocy + hy, mz = k * ocz + hz;  // k times its midpoint
    const double kx = k * ex, ky = k * ey, kz = k * ez;
    const double ahx = std::fabs(hx), ahy = std::fabs(hy), ahz = std::fabs(hz);
    // Each comparison says "separated", so a NaN (false) never rejects.
    if (std::fabs(mx) > kx + ahx || std::fabs(my) > ky + ahy || std::fabs(mz) > kz + ahz) return false;
    if (std::fabs(my * hz - mz * hy) > ky * ahz + kz * ahy) return false;
    if (std::fabs(mz * hx - mx * hz) > kx * ahz + kz * ahx) return false;
    if (std::fabs(mx * hy - my * hx) > kx * ahy + ky * ahx) return false;
    return true;
}

// How much more than `m` the finite box may be widened with the segment still provably
// missing it: a lower bound on the largest such widening, capped at `cap`; 0 when
// MeetsWidened(s, box, m) may be true (or for a NaN). The same separating axes as
// MeetsWidened, each giving the widening up to which it still separates; the reach that
// bounds an unbounded ray counts the cap. (A sample found far from this frame's changes
// is not tested again while they move less than this: block_tracer.cpp.)
inline double ClearanceWidened(const Segment &s, const Box &box, double m, double cap) {
    const double ox = s.origin[0], oy = s.origin[1], oz = s.origin[2];
    const double dx = s.direction[0], dy = s.direction[1], dz = s.direction[2];
    const double cx = 0.5 * (box.lo.x + box.hi.x), cy = 0.5 * (box.lo.y + box.hi.y), cz = 0.5 * (box.lo.z + box.hi.z);
    const double ex = 0.5 * (box.hi.x - box.lo.x) + m, ey = 0.5 * (box.hi.y - box.lo.y) + m,
                 ez = 0.5 * (box.hi.z - box.lo.z) + m;
    const double ocx = ox - cx, ocy = oy - cy, ocz = oz - cz;
    const double k = std::max(std::fabs(dx), std::max(std::fabs(dy), std::fabs(dz)));
    const double reach = std::fabs(ocx) + std::fabs(ocy) + std::fabs(ocz) + ex + ey + ez + 3.0 * cap;
    const double half = 0.5 * std::min(double(s.length) * k, reach);
    const double hx = half * dx, hy = half * dy, hz = half * dz;
    const double mx = k * ocx + hx, my = k * ocy + hy, mz = k * ocz + hz;
    const double ahx = std::fabs(hx), ahy = std::fabs(hy), ahz = std::fabs(hz);
    if (std::isnan(mx + my + mz)) return 0.0;  // std::max below would drop a NaN
    // The box's own axes: |m_a| > k (e_a + w) + |h_a| for every w below (|m_a| - k e_a - |h_a|) / k.
    double w = std::max(std::fabs(mx) - k * ex - ahx,
                        std::max(std::fabs(my) - k * ey - ahy, std::fabs(mz) - k * ez - ahz)) / k;
    // Separated by its own axes (most segments far from a change are): that bound will do.
    if (w > 0.0) return std::min(w, cap);
    // The cross axes: |my hz - mz hy| > k (ey + w) |hz| + k (ez + w) |hy|, and so on.
    const double sx = ahz + ahy, sy = ahz + ahx, sz = ahy + ahx;
    if (sx > 0) w = std::max(w, (std::fabs(my * hz - mz * hy) - k * (ey * ahz + ez * ahy)) / (k * sx));
    if (sy > 0) w = std::max(w, (std::fabs(mz * hx - mx * hz) - k * (ex * ahz + ez * ahx)) / (k * sy));
    if (sz > 0) w = std::max(w, (std::fabs(mx * hy - my * hx) - k * (ex * ahy + ey * ahx)) / (k * sz));
    return w > 0.0 ? std::min(w, cap) : 0.0;  // a NaN gives 0
}

// True when the ray a segment stands for may pass through the hull (box, then capsule).
bool MayMeet(const Segment &s, const Hull &hull);

// What MayMeet(segment, hull) works out from the hull alone: a frame tests tens of
// thousands of segments against the same few hulls (ChangeIndex prepares them once).
struct HullTest {
    bool empty = true;
    bool finite = false;
    Vec3 centre{0.0, 0.0, 0.0};
    double halfExtent = 0.0;     // max norm
    Vec3 axis{0.0, 0.0, 0.0};    // the capsule's b - a
    double axisLength = 0.0;
};
HullTest PrepareHullTest(const Hull &hull);
// MayMeet(s, hull) with `test` = PrepareHullTest(hull): the same arithmetic, the same answer.
bool MayMeet(const Segment &s, const Hull &hull, const HullTest &test);

}  // namespace povrayfc

#endif
