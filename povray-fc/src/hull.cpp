// Conservative segment tests against changed hulls: slab test, then segment-capsule
// distance or the separating axes of a segment and a thick triangle.
#include "povrayfc/hull.h"

#include <algorithm>
#include <stdexcept>

namespace povrayfc {

namespace {

Vec3 Centre(const Box &b) { return 0.5 * (b.lo + b.hi); }
double HalfExtent(const Box &b) {
    const Vec3 e = b.Extent();
    return 0.5 * std::max({e.x, e.y, e.z});
}

// A box widened by a relative hair: POV-Ray keeps object bounds in single precision.
Box Widened(const Box &b) {
    double scale = 0.0;
    for (int a = 0; a < 3; ++a) scale = std::max({scale, std::fabs(b.lo[a]), std::fabs(b.hi[a])});
    const double m = 0x1p-20 * scale + 1e-30;
    return Box{b.lo - Vec3{m, m, m}, b.hi + Vec3{m, m, m}};
}

Vec3 Origin(const Segment &s) { return Vec3{s.origin[0], s.origin[1], s.origin[2]}; }
Vec3 Direction(const Segment &s) { return Vec3{s.direction[0], s.direction[1], s.direction[2]}; }

// Distance from p to the segment [a, a + ab].
double PointSegmentDistance(const Vec3 &p, const Vec3 &a, const Vec3 &ab) {
    const double len2 = Dot(ab, ab);
    double t = len2 > 0.0 ? Dot(p - a, ab) / len2 : 0.0;
    t = std::clamp(t, 0.0, 1.0);
    return Norm(p - (a + t * ab));
}

// Lower bound (up to rounding the caller's margin covers) on the distance between the
// segments [p1, p1 + d1] and [p2, p2 + d2]; Ericson, Real-Time Collision Detection 5.1.9.
// Returns -1 (meaning "may touch") for nearly parallel segments, where the closest pair
// is ill-conditioned and a rounded solution could overstate the distance.
double SegmentSegmentDistance(const Vec3 &p1, const Vec3 &d1, const Vec3 &p2, const Vec3 &d2) {
    const Vec3 r = p1 - p2;
    const double a = Dot(d1, d1), e = Dot(d2, d2), f = Dot(d2, r);
    if (a <= 0.0) return PointSegmentDistance(p1, p2, d2);
    if (e <= 0.0) return PointSegmentDistance(p2, p1, d1);
    const double b = Dot(d1, d2), c = Dot(d1, r);
    const double denom = a * e - b * b;  // a e sin^2(angle)
    if (denom <= 1e-6 * a * e) return -1.0;
    double s = std::clamp((b * f - c * e) / denom, 0.0, 1.0);
    double t = (b * s + f) / e;
    if (t < 0.0) {
        t = 0.0;
        s = std::clamp(-c / a, 0.0, 1.0);
    } else if (t > 1.0) {
        t = 1.0;
        s = std::clamp((b - c) / a, 0.0, 1.0);
    }
    return Norm((p1 + s * d1) - (p2 + t * d2));
}

// The ray may pass through the hull's thick triangle (its box already met, margin m).
bool MayMeetTriangle(const Segment &s, const Hull &hull, const HullTest &test, double m) {
    const Triangle &tri = hull.triangle;
    const Vec3 o = Origin(s), d = Direction(s);
    // A point of the traced ray in the thick triangle lies in the hull's box, and a point of
    // the segment within m of it (in each coordinate) in the box widened by m: clip the
    // segment to the box widened by 3m, the rest covering the rounding of the clip.
    double t0 = 0.0, t1 = s.length;
    for (int a = 0; a < 3; ++a) {
        const double lo = hull.box.lo[a] - 3.0 * m, hi = hull.box.hi[a] + 3.0 * m;
        if (d[a] == 0.0) {
            if (o[a] < lo || o[a] > hi) return false;
            continue;
        }
        const double ta = (lo - o[a]) / d[a], tb = (hi - o[a]) / d[a];
        t0 = std::max(t0, std::min(ta, tb));
        t1 = std::min(t1, std::max(ta, tb));
    }
    if (std::isnan(t0) || std::isnan(t1)) return true;
    if (t0 > t1) return false;
    const Vec3 p0 = o + t0 * d, p1 = o + t1 * d;
    // Separating axes of a segment and a triangle: the triangle's normal, its edges'
    // normals in its plane, and the segment's direction across each edge. On each, the
    // triangle's extent is widened by its thickness and twice the margin (a point within m
    // in each coordinate lies within sqrt(3) m), scaled by the axis's length: any axis
    // that separates the widened shapes proves the ray misses (its direction need not be
    // exact, only the projections taken with it; their rounding is far inside m).
    const double widening = tri.thickness + 2.0 * m;
    auto separates = [&](const Vec3 &axis, double low, double high, double norm) {
        const double r = widening * norm;
        const double s0 = Dot(p0, axis), s1 = Dot(p1, axis);
        return std::max(s0, s1) < low - r || std::min(s0, s1) > high + r;
    };
    for (int i = 0; i < 4; ++i)
        if (separates(test.triangleAxes[i], test.triangleLow[i], test.triangleHigh[i], test.triangleAxisNorm[i]))
            return false;
    for (int i = 0; i < 3; ++i) {
        const Vec3 axis = Cross(d, test.triangleEdges[i]);
        const double pa = Dot(tri.a, axis), pb = Dot(tri.b, axis), pc = Dot(tri.c, axis);
        if (separates(axis, std::min({pa, pb, pc}), std::max({pa, pb, pc}), Norm(axis))) return false;
    }
    return true;
}

}  // namespace

Hull MakeHull(const Box &box) {
    if (box.HasNaN()) throw std::invalid_argument("MakeHull: box contains NaN: " + ToString(box));
    Hull h;
    h.box = box.Empty() ? Box() : (box.IsFinite() ? Widened(box) : box);
    return h;
}

Hull MakeHull(const Box &box, const Capsule &capsule) {
    if (capsule.a.HasNaN() || capsule.b.HasNaN() || std::isnan(capsule.radius))
        throw std::invalid_argument("MakeHull: capsule contains NaN");
    Hull h = MakeHull(box);
    if (h.box.Empty() || !h.box.IsFinite() || !capsule.a.IsFinite() || !capsule.b.IsFinite() ||
        !std::isfinite(capsule.radius))
        return h;
    h.hasCapsule = true;
    h.capsule = capsule;
    // The same relative hair as the box: the capsule comes from rounded transforms too.
    double scale = std::fabs(capsule.radius);
    for (int a = 0; a < 3; ++a) scale = std::max({scale, std::fabs(capsule.a[a]), std::fabs(capsule.b[a])});
    h.capsule.radius = std::fabs(capsule.radius) + 0x1p-20 * scale + 1e-30;
    return h;
}

Hull MakeHull(const Box &box, const Triangle &triangle) {
    if (triangle.a.HasNaN() || triangle.b.HasNaN() || triangle.c.HasNaN() || std::isnan(triangle.thickness))
        throw std::invalid_argument("MakeHull: triangle contains NaN");
    Hull h = MakeHull(box);
    if (h.box.Empty() || !h.box.IsFinite() || !triangle.a.IsFinite() || !triangle.b.IsFinite() ||
        !triangle.c.IsFinite() || !std::isfinite(triangle.thickness))
        return h;
    h.hasTriangle = true;
    h.triangle = triangle;
    // The same relative hair as the box, and the box made to hold the thick triangle.
    double scale = std::fabs(triangle.thickness);
    for (const Vec3 *v : {&triangle.a, &triangle.b, &triangle.c})
        for (int a = 0; a < 3; ++a) scale = std::max(scale, std::fabs((*v)[a]));
    h.triangle.thickness = std::fabs(triangle.thickness) + 0x1p-20 * scale + 1e-30;
    const double t = h.triangle.thickness;
    Box thick;
    for (const Vec3 *v : {&triangle.a, &triangle.b, &triangle.c}) thick.Grow(*v - Vec3{t, t, t}).Grow(*v + Vec3{t, t, t});
    h.box = Intersection(h.box, thick);
    if (h.box.Empty()) h.hasTriangle = false;  // rounding apart, never: an empty box meets nothing
    return h;
}

bool MayMeet(const Segment &s, const Box &box) {
    if (box.Empty()) return false;
    if (!box.IsFinite()) return true;
    return MeetsWidened(s, box, SegmentMargin(s, Centre(box), HalfExtent(box)));
}

bool MayMeet(const Segment &s, const Hull &hull) { return MayMeet(s, hull, PrepareHullTest(hull)); }

HullTest PrepareHullTest(const Hull &hull) {
    HullTest t;
    t.empty = hull.box.Empty();
    t.finite = hull.box.IsFinite();
    if (t.empty || !t.finite) return t;
    t.centre = Centre(hull.box);
    t.halfExtent = HalfExtent(hull.box);
    t.axis = hull.capsule.b - hull.capsule.a;
    t.axisLength = Norm(t.axis);
    if (hull.hasTriangle) {
        const Triangle &tri = hull.triangle;
        t.triangleEdges[0] = tri.b - tri.a;
        t.triangleEdges[1] = tri.c - tri.b;
        t.triangleEdges[2] = tri.a - tri.c;
        const Vec3 normal = Cross(t.triangleEdges[0], t.triangleEdges[1]);
        t.triangleAxes[0] = normal;
        for (int i = 0; i < 3; ++i) t.triangleAxes[i + 1] = Cross(normal, t.triangleEdges[i]);
        for (int i = 0; i < 4; ++i) {
            const double pa = Dot(tri.a, t.triangleAxes[i]), pb = Dot(tri.b, t.triangleAxes[i]),
                         pc = Dot(tri.c, t.triangleAxes[i]);
            t.triangleLow[i] = std::min({pa, pb, pc});
            t.triangleHigh[i] = std::max({pa, pb, pc});
            t.triangleAxisNorm[i] = Norm(t.triangleAxes[i]);
        }
    }
    return t;
}

bool MayMeet(const Segment &s, const Hull &hull, const HullTest &test) {
    // The box (as MayMeet(s, box)), then the capsule, with one margin for both.
    if (test.empty) return false;
    if (!test.finite) return true;
    const double m = SegmentMargin(s, test.centre, test.halfExtent);
    if (!MeetsWidened(s, hull.box, m)) return false;
    if (hull.hasTriangle) return MayMeetTriangle(s, hull, test, m);
    if (!hull.hasCapsule) return true;
    const Capsule &c = hull.capsule;
    const double reach = c.radius + m;
    const Vec3 o = Origin(s), d = Direction(s);
    // Only the part of the ray within reach of the capsule's axis matters; clipping an
    // unbounded ray there keeps the arithmetic finite.
    const double dn = Norm(d);
    const double far = (Norm(o - c.a) + test.axisLength + reach) / dn * (1.0 + 1e-9);
    const double length = std::min(double(s.length), far);
    const double dist = SegmentSegmentDistance(o, length * d, c.a, test.axis);
    return dist <= reach;
}


}  // namespace povrayfc
