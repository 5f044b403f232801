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
// cones, whose boxes are loose when slanted) or by a thick triangle (a mesh's triangle). A
// point can only have changed if it lies in the box and, when there is one, in the capsule
// or the triangle.
struct Hull {
    Box box;
    bool hasCapsule = false;
    Capsule capsule;
    bool hasTriangle = false;
    Triangle triangle;
};

// A hull around `box` (and `capsule`), widened by a relative hair so that single-precision
// bounding boxes of POV-Ray's objects (rounded to nearest, not outward) still contain the
// object. Throws std::invalid_argument for NaN; an empty box gives an empty hull.
Hull MakeHull(const Box &box);
Hull MakeHull(const Box &box, const Capsule &capsule);
// The triangle is thickened by the same hair (a NaN throws; a triangle that is not finite
// leaves the box alone).
Hull MakeHull(const Box &box, const Triangle &triangle);

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

// True when the ray a segment stands for may pass through the closed box (a slab test
// against the box widened by SegmentMargin). Never false for a ray that touches it.
bool MayMeet(const Segment &s, const Box &box);
// The separating-axis test's quantities for a segment and `box` widened by `m`, every
// length scaled by k, the direction's largest component (> 0, see MakeSegment): a slab
// test's three divisions cost more than the rest of the test together, and this runs for
// every stored segment near a change every frame. Scaling spares the division that bounds
// an unbounded ray: the comparisons scale alike, and the rounding this moves is ~1e-16 of
// the magnitudes, far inside m. Beyond `reach` / k along the ray every point is farther
// from the box's centre than any point of the box widened by `spare` more (|v|_2 <= |v|_1),
// which bounds an unbounded ray.
struct ScaledSegmentBox {
    double k;
    double ex, ey, ez;     // the widened box's half extents (not scaled)
    double mx, my, mz;     // k times the segment's midpoint, from the box's centre
    double hx, hy, hz;     // k times half the segment
    double ahx, ahy, ahz;  // |hx|, |hy|, |hz|
};
inline ScaledSegmentBox ScaleSegmentBox(const Segment &s, const Box &box, double m, double spare) {
    ScaledSegmentBox q;
    const double dx = s.direction[0], dy = s.direction[1], dz = s.direction[2];
    const double ocx = s.origin[0] - 0.5 * (box.lo.x + box.hi.x), ocy = s.origin[1] - 0.5 * (box.lo.y + box.hi.y),
                 ocz = s.origin[2] - 0.5 * (box.lo.z + box.hi.z);
    q.ex = 0.5 * (box.hi.x - box.lo.x) + m;
    q.ey = 0.5 * (box.hi.y - box.lo.y) + m;
    q.ez = 0.5 * (box.hi.z - box.lo.z) + m;
    q.k = std::max(std::fabs(dx), std::max(std::fabs(dy), std::fabs(dz)));
    const double reach = std::fabs(ocx) + std::fabs(ocy) + std::fabs(ocz) + q.ex + q.ey + q.ez + 3.0 * spare;
    const double half = 0.5 * std::min(double(s.length) * q.k, reach);
    q.hx = half * dx, q.hy = half * dy, q.hz = half * dz;
    q.mx = q.k * ocx + q.hx, q.my = q.k * ocy + q.hy, q.mz = q.k * ocz + q.hz;
    q.ahx = std::fabs(q.hx), q.ahy = std::fabs(q.hy), q.ahz = std::fabs(q.hz);
    return q;
}

// The separating-axis test against `box` widened by `margin` (finite boxes only): false
// only when the segment provably misses it; a NaN anywhere gives true.
inline bool MeetsWidened(const Segment &s, const Box &box, double m) {
    // The box's three axes and their cross products with the segment, all multiplications.
    const ScaledSegmentBox q = ScaleSegmentBox(s, box, m, 0.0);
    const double kx = q.k * q.ex, ky = q.k * q.ey, kz = q.k * q.ez;
    // Each comparison says "separated", so a NaN (false) never rejects.
    if (std::fabs(q.mx) > kx + q.ahx || std::fabs(q.my) > ky + q.ahy || std::fabs(q.mz) > kz + q.ahz) return false;
    if (std::fabs(q.my * q.hz - q.mz * q.hy) > ky * q.ahz + kz * q.ahy) return false;
    if (std::fabs(q.mz * q.hx - q.mx * q.hz) > kx * q.ahz + kz * q.ahx) return false;
    if (std::fabs(q.mx * q.hy - q.my * q.hx) > kx * q.ahy + ky * q.ahx) return false;
    return true;
}

// How much more than `m` the finite box may be widened with the segment still provably
// missing it: a lower bound on the largest such widening, capped at `cap`; 0 when
// MeetsWidened(s, box, m) may be true (or for a NaN). The same separating axes as
// MeetsWidened, each giving the widening up to which it still separates. (A sample found
// far from this frame's changes is not tested again while they move less than this:
// block_tracer.cpp.)
inline double ClearanceWidened(const Segment &s, const Box &box, double m, double cap) {
    const ScaledSegmentBox q = ScaleSegmentBox(s, box, m, cap);
    const double k = q.k;
    if (std::isnan(q.mx + q.my + q.mz)) return 0.0;  // std::max below would drop a NaN
    // The box's own axes: |m_a| > k (e_a + w) + |h_a| for every w below (|m_a| - k e_a - |h_a|) / k.
    double w = std::max(std::fabs(q.mx) - k * q.ex - q.ahx,
                        std::max(std::fabs(q.my) - k * q.ey - q.ahy, std::fabs(q.mz) - k * q.ez - q.ahz)) / k;
    // Separated by its own axes (most segments far from a change are): that bound will do.
    if (w > 0.0) return std::min(w, cap);
    // The cross axes: |my hz - mz hy| > k (ey + w) |hz| + k (ez + w) |hy|, and so on.
    const double sx = q.ahz + q.ahy, sy = q.ahz + q.ahx, sz = q.ahy + q.ahx;
    if (sx > 0) w = std::max(w, (std::fabs(q.my * q.hz - q.mz * q.hy) - k * (q.ey * q.ahz + q.ez * q.ahy)) / (k * sx));
    if (sy > 0) w = std::max(w, (std::fabs(q.mz * q.hx - q.mx * q.hz) - k * (q.ex * q.ahz + q.ez * q.ahx)) / (k * sy));
    if (sz > 0) w = std::max(w, (std::fabs(q.mx * q.hy - q.my * q.hx) - k * (q.ex * q.ahy + q.ey * q.ahx)) / (k * sz));
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
    // The triangle's separating axes that do not hang on the segment (its normal and, in its
    // plane, the normals of its edges) with its extent along each, and its edges.
    Vec3 triangleAxes[4];
    double triangleLow[4] = {0.0, 0.0, 0.0, 0.0}, triangleHigh[4] = {0.0, 0.0, 0.0, 0.0};
    double triangleAxisNorm[4] = {0.0, 0.0, 0.0, 0.0};
    Vec3 triangleEdges[3];
};
HullTest PrepareHullTest(const Hull &hull);
// MayMeet(s, hull) with `test` = PrepareHullTest(hull): the same arithmetic, the same answer.
bool MayMeet(const Segment &s, const Hull &hull, const HullTest &test);

}  // namespace povrayfc

#endif
