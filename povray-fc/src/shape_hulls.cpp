// Capsule hulls of cones, cylinders and spheres.
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

// The most the first `rows` rows of m stretch a unit vector of their span: ||c m|| over
// ||c|| = 1 is the square root of the largest eigenvalue of the rows' Gram matrix, which
// no row sum of its absolute values is below (Gershgorin). Exact when the rows are
// orthogonal, as rotations and scalings leave them; a shear only loosens it. The last
// factor covers the rounding of the dot products and the root (a few ulps).
double LargestStretch(const Matrix4 &m, int rows) {
    double bound = 0.0;
    for (int i = 0; i < rows; ++i) {
        double sum = 0.0;
        for (int j = 0; j < rows; ++j)
            sum += std::fabs(m[i][0] * m[j][0] + m[i][1] * m[j][1] + m[i][2] * m[j][2]);
        bound = std::max(bound, sum);
    }
    return std::sqrt(bound) * (1.0 + 0x1p-40);
}

}  // namespace

Capsule CapsuleOfUnitCylinder(const Matrix4 &m) {
    Capsule c;
    c.a = Point(m, Vec3{0, 0, 0});
    c.b = Point(m, Vec3{0, 0, 1});
    c.radius = LargestStretch(m, 2);
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
    c.a = c.b = Point(*m, p);
    c.radius = radius * LargestStretch(*m, 3);
    return c;
}

}  // namespace povrayfc
