// Capsule hulls of cones, cylinders, turned boxes, spheres and ellipsoids.
#include "povrayfc/shape_hulls.h"

#include <algorithm>
#include <cmath>

namespace povrayfc {

namespace {

Vec3 Point(const Matrix4 &m, const Vec3 &v) {
    Vec3 r;
    for (int i = 0; i < 3; ++i) r[i] = v.x * m[0][i] + v.y * m[1][i] + v.z * m[2][i] + m[3][i];
    return r;
}

double Length(const Vec3 &v) { return std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z); }

// The largest eigenvalue of the symmetric g is no more than any of its rows' sums of
// absolute values (Gershgorin): exact for a diagonal g.
double GershgorinBound(const double g[3][3], int n) {
    double bound = 0.0;
    for (int i = 0; i < n; ++i) bound = std::max(bound, std::fabs(g[i][0]) + std::fabs(g[i][1]) + std::fabs(g[i][2]));
    return bound;
}

// The factor that covers the rounding of a few dot products and a square root.
constexpr double kRounding = 1.0 + 0x1p-40;

// The most the first `rows` rows of m stretch a unit vector of their span: ||c m|| over
// ||c|| = 1 is the square root of the largest eigenvalue of the rows' Gram matrix (bounded
// by Gershgorin). Exact when the rows are orthogonal, as rotations and scalings leave them;
// a shear only loosens it.
double LargestStretch(const Matrix4 &m, int rows) {
    double g[3][3] = {};
    for (int i = 0; i < rows; ++i)
        for (int j = 0; j < rows; ++j) g[i][j] = m[i][0] * m[j][0] + m[i][1] * m[j][1] + m[i][2] * m[j][2];
    return std::sqrt(GershgorinBound(g, rows)) * kRounding;
}

}  // namespace

Capsule CapsuleOfUnitCylinder(const Matrix4 &m) {
    Capsule c;
    c.a = Point(m, Vec3{0, 0, 0});
    c.b = Point(m, Vec3{0, 0, 1});
    c.radius = LargestStretch(m, 2);
    return c;
}

int CapsulesOfUnitCone(const Matrix4 &m, double dist, Capsule out[2]) {
    // At height z a cross-section of radius z lies within z times the cross-section's
    // stretch of the axis's point there: the narrow half within its middle's radius.
    const double stretch = LargestStretch(m, 2);
    const double middle = 0.5 * (dist + 1.0);
    out[0].a = Point(m, Vec3{0, 0, dist});
    out[0].b = out[1].a = Point(m, Vec3{0, 0, middle});
    out[1].b = Point(m, Vec3{0, 0, 1});
    out[0].radius = middle * stretch * kRounding;
    out[1].radius = stretch;
    return 2;
}

Capsule CapsuleOfBox(const double lo[3], const double hi[3], const Matrix4 &m) {
    // A point of the box is its centre's image plus x h_0 m_0 + y h_1 m_1 + z h_2 m_2 with
    // |x|, |y|, |z| <= 1 (h: the half extents, m_i: the rows). Along the longest edge's
    // direction k that is the axis; across it the rest, whose length is largest at a corner
    // of the cross-section (a convex function of (x, y) is, over a rectangle).
    Vec3 edge[3];
    double length[3];
    for (int i = 0; i < 3; ++i) {
        const double h = 0.5 * std::fabs(hi[i] - lo[i]);
        edge[i] = Vec3{h * m[i][0], h * m[i][1], h * m[i][2]};
        length[i] = Length(edge[i]);
    }
    const int k = length[0] >= length[1] ? (length[0] >= length[2] ? 0 : 2) : (length[1] >= length[2] ? 1 : 2);
    const Vec3 u = edge[(k + 1) % 3], v = edge[(k + 2) % 3];
    const Vec3 centre = Point(m, Vec3{0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2])});
    Capsule c;
    c.a = centre - edge[k];
    c.b = centre + edge[k];
    c.radius = std::max(Length(u + v), Length(u - v)) * kRounding;
    return c;
}

Capsule CapsuleOfSphere(const double centre[3], double radius, const Matrix4 *m) {
    Capsule c;
    const Vec3 p{centre[0], centre[1], centre[2]};
    if (m == nullptr) {
        c.a = c.b = p;
        c.radius = radius;
        return c;
    }
    // An ellipsoid: its points are q m for q in the ball, the centre's image plus radius
    // times u A (|u| <= 1, A the linear part). Along a unit axis e that offset is at most
    // radius |A e|, and across it at most radius times the stretch of A P (P = I - e e^T;
    // the square root of the largest eigenvalue of P A^T A P): it lies in the capsule of that
    // half-length and that radius about its centre, whichever e is; e near A's longest axis
    // (a few steps of the power method on G = A^T A) makes it thin.
    double g[3][3];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) g[i][j] = (*m)[0][i] * (*m)[0][j] + (*m)[1][i] * (*m)[1][j] + (*m)[2][i] * (*m)[2][j];
    const double ball = std::sqrt(GershgorinBound(g, 3)) * kRounding;
    int widest = 0;
    for (int i = 1; i < 3; ++i)
        if (g[i][i] > g[widest][widest]) widest = i;
    double e[3] = {g[widest][0], g[widest][1], g[widest][2]};
    for (int step = 0; step < 32; ++step) {
        double next[3];
        for (int i = 0; i < 3; ++i) next[i] = g[i][0] * e[0] + g[i][1] * e[1] + g[i][2] * e[2];
        const double n = std::sqrt(next[0] * next[0] + next[1] * next[1] + next[2] * next[2]);
        if (!(n > 0.0) || !std::isfinite(n)) break;
        for (int i = 0; i < 3; ++i) e[i] = next[i] / n;
    }
    const double n = std::sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
    c.a = c.b = Point(*m, p);
    c.radius = radius * ball;
    if (!(n > 0.0) || !std::isfinite(n)) return c;
    for (double &v : e) v /= n;
    // Across e: the largest eigenvalue of G on the plane normal to e, exactly from the 2x2
    // matrix of G in an orthonormal basis (f, h) of that plane.
    double along[3];
    for (int i = 0; i < 3; ++i) along[i] = (*m)[i][0] * e[0] + (*m)[i][1] * e[1] + (*m)[i][2] * e[2];  // A e
    const int away = std::fabs(e[0]) < std::fabs(e[1]) ? (std::fabs(e[0]) < std::fabs(e[2]) ? 0 : 2)
                                                       : (std::fabs(e[1]) < std::fabs(e[2]) ? 1 : 2);
    double f[3] = {0, 0, 0};
    f[away] = 1.0;
    const double fe = f[0] * e[0] + f[1] * e[1] + f[2] * e[2];
    for (int i = 0; i < 3; ++i) f[i] -= fe * e[i];
    const double fn = std::sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    for (double &v : f) v /= fn;
    const double h[3] = {e[1] * f[2] - e[2] * f[1], e[2] * f[0] - e[0] * f[2], e[0] * f[1] - e[1] * f[0]};
    auto quadratic = [&g](const double *x, const double *y) {
        double sum = 0.0;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) sum += x[i] * g[i][j] * y[j];
        return sum;
    };
    const double gff = quadratic(f, f), ghh = quadratic(h, h), gfh = quadratic(f, h);
    const double largest = 0.5 * (gff + ghh) + std::sqrt(0.25 * (gff - ghh) * (gff - ghh) + gfh * gfh);
    const double half = radius * std::sqrt(along[0] * along[0] + along[1] * along[1] + along[2] * along[2]) * kRounding;
    // A rounded basis and rounded products move that eigenvalue by a few ulps of G's largest,
    // its root by about 2^-26 of the longest axis for a thin ellipsoid: the last term covers
    // that many times over.
    const double thin = radius * (std::sqrt(std::max(0.0, largest)) * kRounding + 0x1p-20 * ball);
    // A round ellipsoid gains nothing from an axis (and a rounded e could make it worse).
    if (!(thin < 0.9 * c.radius) || !std::isfinite(half)) return c;
    const Vec3 axis{e[0] * half, e[1] * half, e[2] * half};
    c.a = c.a - axis;
    c.b = c.b + axis;
    c.radius = thin;
    return c;
}

}  // namespace povrayfc
