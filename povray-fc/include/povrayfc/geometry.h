// Minimal 3D point/vector and axis-aligned box types shared by the grid, walker and change set.
#ifndef POVRAYFC_GEOMETRY_H
#define POVRAYFC_GEOMETRY_H

#include <cmath>
#include <limits>
#include <string>

namespace povrayfc {

// Plain aggregate so the POV-Ray hooks can write Vec3{v[X], v[Y], v[Z]} without conversions.
struct Vec3 {
    double x = 0, y = 0, z = 0;

    double operator[](int axis) const { return axis == 0 ? x : (axis == 1 ? y : z); }
    double &operator[](int axis) { return axis == 0 ? x : (axis == 1 ? y : z); }

    bool IsFinite() const { return std::isfinite(x) && std::isfinite(y) && std::isfinite(z); }
    bool HasNaN() const { return std::isnan(x) || std::isnan(y) || std::isnan(z); }
};

inline Vec3 operator+(const Vec3 &a, const Vec3 &b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3 operator-(const Vec3 &a, const Vec3 &b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3 operator*(double s, const Vec3 &v) { return {s * v.x, s * v.y, s * v.z}; }
inline double Dot(const Vec3 &a, const Vec3 &b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline double Norm(const Vec3 &a) { return std::sqrt(Dot(a, a)); }
inline Vec3 Cross(const Vec3 &a, const Vec3 &b) {
    return Vec3{a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline Vec3 Min(const Vec3 &a, const Vec3 &b) {
    return {std::fmin(a.x, b.x), std::fmin(a.y, b.y), std::fmin(a.z, b.z)};
}
inline Vec3 Max(const Vec3 &a, const Vec3 &b) {
    return {std::fmax(a.x, b.x), std::fmax(a.y, b.y), std::fmax(a.z, b.z)};
}

// Closed axis-aligned box [lo, hi]. A default-constructed Box is empty (lo=+inf, hi=-inf)
// so that growing it by points or boxes starts from nothing.
struct Box {
    Vec3 lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
            std::numeric_limits<double>::infinity()};
    Vec3 hi{-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
            -std::numeric_limits<double>::infinity()};

    // Empty when some axis has lo > hi. A box with a NaN coordinate counts as empty too
    // (the comparison fails); callers that must not ignore NaN check HasNaN() first.
    bool Empty() const { return !(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z); }
    bool HasNaN() const { return lo.HasNaN() || hi.HasNaN(); }
    bool IsFinite() const { return lo.IsFinite() && hi.IsFinite(); }
    Vec3 Extent() const { return hi - lo; }

    // Closed containment: points on the faces are inside.
    bool Contains(const Vec3 &p) const {
        return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y && p.z >= lo.z &&
               p.z <= hi.z;
    }
    // True when b lies inside this box (faces may coincide). An empty b is inside anything.
    // p lies within `distance` of the box (inside it, for 0).
    bool Near(const Vec3 &p, double distance) const {
        return p.x >= lo.x - distance && p.x <= hi.x + distance && p.y >= lo.y - distance && p.y <= hi.y + distance &&
               p.z >= lo.z - distance && p.z <= hi.z + distance;
    }
    bool Contains(const Box &b) const {
        if (b.Empty()) return true;
        return b.lo.x >= lo.x && b.hi.x <= hi.x && b.lo.y >= lo.y && b.hi.y <= hi.y &&
               b.lo.z >= lo.z && b.hi.z <= hi.z;
    }
    // Closed overlap: boxes sharing only a face, edge or corner overlap.
    bool Overlaps(const Box &b) const {
        return lo.x <= b.hi.x && b.lo.x <= hi.x && lo.y <= b.hi.y && b.lo.y <= hi.y &&
               lo.z <= b.hi.z && b.lo.z <= hi.z;
    }

    Box &Grow(const Vec3 &p) {
        lo = Min(lo, p);
        hi = Max(hi, p);
        return *this;
    }
    Box &Grow(const Box &b) {
        if (b.Empty()) return *this;
        lo = Min(lo, b.lo);
        hi = Max(hi, b.hi);
        return *this;
    }
};

// Every point within `radius` of the segment [a, b] (a sphere when a == b): a tight
// conservative hull of cylinders, cones and spheres, whose bounding boxes are loose.
struct Capsule {
    Vec3 a, b;
    double radius = 0.0;

    // Distance from p to the segment [a, b].
    double AxisDistance(const Vec3 &p) const {
        const Vec3 ab = b - a, ap = p - a;
        const double len2 = ab.x * ab.x + ab.y * ab.y + ab.z * ab.z;
        double t = len2 > 0.0 ? (ap.x * ab.x + ap.y * ab.y + ap.z * ab.z) / len2 : 0.0;
        t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
        const Vec3 d = p - (a + t * ab);
        return std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
    }
    // True when the closed box may meet the capsule (conservative: tests the box's
    // circumscribed sphere against the capsule).
    bool MayMeet(const Box &box) const {
        const Vec3 c = 0.5 * (box.lo + box.hi), e = box.hi - box.lo;
        const double halfDiagonal = 0.5 * std::sqrt(e.x * e.x + e.y * e.y + e.z * e.z);
        return AxisDistance(c) <= (radius + halfDiagonal) * (1.0 + 1e-9) + 1e-12;
    }
};

// Every point within `thickness` of the triangle [a, b, c]: a mesh's triangle, whose
// plane POV-Ray keeps in single precision (a tight hull where its box is loose).
struct Triangle {
    Vec3 a, b, c;
    double thickness = 0.0;
};

inline Box Union(const Box &a, const Box &b) {
    Box r = a;
    r.Grow(b);
    return r;
}

inline Box Intersection(const Box &a, const Box &b) {
    return Box{Max(a.lo, b.lo), Min(a.hi, b.hi)};
}

// "[(x, y, z), (x, y, z)]" with full precision, for error messages and change reasons.
std::string ToString(const Vec3 &v);
std::string ToString(const Box &b);

}  // namespace povrayfc

#endif
