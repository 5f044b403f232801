// Conservative segment tests against changed hulls: slab test, then segment-capsule distance.
#include "povrayfc/hull.h"

#include <algorithm>
#include <stdexcept>

namespace povrayfc {

namespace {

double Dot(const Vec3 &a, const Vec3 &b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
double Norm(const Vec3 &a) { return std::sqrt(Dot(a, a)); }

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
    return t;
}

bool MayMeet(const Segment &s, const Hull &hull, const HullTest &test) {
    // The box (as MayMeet(s, box)), then the capsule, with one margin for both.
    if (test.empty) return false;
    if (!test.finite) return true;
    const double m = SegmentMargin(s, test.centre, test.halfExtent);
    if (!MeetsWidened(s, hull.box, m)) return false;
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
