// Capsule hulls of cones, cylinders and spheres.
#include "povrayfc/shape_hulls.h"

#include <cmath>

namespace povrayfc {

namespace {

Vec3 Point(const Matrix4 &m, const Vec3 &v) {
    Vec3 r;
    for (int i = 0; i < 3; ++i) r[i] = v.x * m[0][i] + v.y * m[1][i] + v.z * m[2][i] + m[3][i];
    return r;
}

double DirectionLength(const Matrix4 &m, int row) {
    return std::sqrt(m[row][0] * m[row][0] + m[row][1] * m[row][1] + m[row][2] * m[row][2]);
}

}  // namespace

Capsule CapsuleOfUnitCylinder(const Matrix4 &m) {
    Capsule c;
    c.a = Point(m, Vec3{0, 0, 0});
    c.b = Point(m, Vec3{0, 0, 1});
    c.radius = DirectionLength(m, 0) + DirectionLength(m, 1);
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
    c.radius = radius * (DirectionLength(*m, 0) + DirectionLength(*m, 1) + DirectionLength(*m, 2));
    return c;
}

}  // namespace povrayfc
