// Tests for the capsule hulls of shapes: every point of the shape lies in the capsule.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "povrayfc/shape_hulls.h"

using namespace povrayfc;

namespace {

void Multiply(const double a[4][4], const double b[4][4], double r[4][4]) {
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            r[i][j] = 0;
            for (int k = 0; k < 4; ++k) r[i][j] += a[i][k] * b[k][j];
        }
}

void RandomTransform(std::mt19937_64 &rng, double m[4][4]) {
    std::uniform_real_distribution<double> u(-1, 1), s(0.1, 3);
    double scale[4][4] = {{s(rng), 0, 0, 0}, {0, s(rng), 0, 0}, {0, 0, s(rng), 0}, {0, 0, 0, 1}};
    const double a = 3 * u(rng), b = 3 * u(rng);
    double rz[4][4] = {{std::cos(a), std::sin(a), 0, 0}, {-std::sin(a), std::cos(a), 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}};
    double rx[4][4] = {{1, 0, 0, 0}, {0, std::cos(b), std::sin(b), 0}, {0, -std::sin(b), std::cos(b), 0}, {0, 0, 0, 1}};
    double shear[4][4] = {{1, 0.3 * u(rng), 0, 0}, {0, 1, 0, 0}, {0.2 * u(rng), 0, 1, 0},
                          {5 * u(rng), 5 * u(rng), 5 * u(rng), 1}};
    double t1[4][4], t2[4][4];
    Multiply(scale, rz, t1);
    Multiply(t1, rx, t2);
    Multiply(t2, shear, m);
}

Vec3 Apply(const double m[4][4], const Vec3 &v) {
    Vec3 r;
    for (int i = 0; i < 3; ++i) r[i] = v.x * m[0][i] + v.y * m[1][i] + v.z * m[2][i] + m[3][i];
    return r;
}

TEST(ShapeHulls, TransformedUnitCylinderLiesInItsCapsule) {
    std::mt19937_64 rng(9);
    std::uniform_real_distribution<double> u(0, 1), angle(0, 6.283185307179586);
    for (int t = 0; t < 200; ++t) {
        double m[4][4];
        RandomTransform(rng, m);
        const Capsule c = CapsuleOfUnitCylinder(m);
        for (int k = 0; k < 2000; ++k) {
            // On the rim: the points farthest from the axis, where a radius too small fails.
            const double a = angle(rng);
            const Vec3 p = Apply(m, Vec3{std::cos(a), std::sin(a), u(rng)});
            // Invariant: points of the cylinder are within the capsule's radius of its axis.
            ASSERT_LE(c.AxisDistance(p), c.radius * (1 + 1e-12)) << t << " " << k;
        }
    }
}

TEST(ShapeHulls, TransformedUnitConeLiesInItsTwoCapsules) {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(0, 1), angle(0, 6.283185307179586);
    for (int t = 0; t < 200; ++t) {
        double m[4][4];
        RandomTransform(rng, m);
        const double dist = 0.9 * u(rng);
        Capsule c[2];
        ASSERT_EQ(CapsulesOfUnitCone(m, dist, c), 2);
        for (int k = 0; k < 2000; ++k) {
            // On the side: the points farthest from the axis at their height.
            const double z = dist + (1.0 - dist) * u(rng), a = angle(rng);
            const Vec3 p = Apply(m, Vec3{z * std::cos(a), z * std::sin(a), z});
            // Invariant: every point of the cone is in one of its capsules.
            ASSERT_TRUE(c[0].AxisDistance(p) <= c[0].radius * (1 + 1e-12) ||
                        c[1].AxisDistance(p) <= c[1].radius * (1 + 1e-12))
                << t << " " << k;
        }
    }
    // The narrow half is thinner: a turned cone from a point (dist 0) of radius 2.
    const double turned[4][4] = {{0, 2, 0, 0}, {-2, 0, 0, 0}, {0, 0, 5, 0}, {1, 1, 1, 1}};
    Capsule c[2];
    CapsulesOfUnitCone(turned, 0.0, c);
    EXPECT_NEAR(c[0].radius, 1.0, 1e-10);
    EXPECT_NEAR(c[1].radius, 2.0, 1e-10);
}

TEST(ShapeHulls, AStretchedEllipsoidGetsACapsuleAlongItsLongAxis) {
    // Stretched three times along x, then turned: the capsule runs along the long axis and
    // is as thin as the short ones.
    const double a = 0.6, stretched[4][4] = {{3 * std::cos(a), 3 * std::sin(a), 0, 0},
                                             {-std::sin(a), std::cos(a), 0, 0},
                                             {0, 0, 1, 0},
                                             {2, 0, 0, 1}};
    const double centre[3] = {0, 0, 0};
    const Capsule c = CapsuleOfSphere(centre, 0.5, &stretched);
    EXPECT_NEAR(c.radius, 0.5, 1e-5);
    const Vec3 axis = c.b - c.a;
    EXPECT_NEAR(std::sqrt(axis.x * axis.x + axis.y * axis.y + axis.z * axis.z), 3.0, 1e-5);
    EXPECT_NEAR(std::fabs(axis.x * std::cos(a) + axis.y * std::sin(a)), 3.0, 1e-5);
}

TEST(ShapeHulls, TransformedBoxLiesInItsCapsule) {
    std::mt19937_64 rng(12);
    std::uniform_real_distribution<double> u(-1, 1), side(0.05, 3);
    for (int t = 0; t < 200; ++t) {
        double m[4][4];
        RandomTransform(rng, m);
        const double lo[3] = {u(rng), u(rng), u(rng)};
        const double hi[3] = {lo[0] + side(rng), lo[1] + side(rng), lo[2] + side(rng)};
        const Capsule c = CapsuleOfBox(lo, hi, m);
        for (int k = 0; k < 500; ++k) {
            // On the surface, corners and edges included: a corner is where a radius too
            // small fails first.
            double q[3];
            for (int i = 0; i < 3; ++i) q[i] = k < 8 ? ((k >> i) & 1 ? hi[i] : lo[i]) : lo[i] + (hi[i] - lo[i]) * (0.5 + 0.5 * u(rng));
            if (k >= 8) q[k % 3] = u(rng) < 0 ? lo[k % 3] : hi[k % 3];
            // Invariant: every point of the box is within the capsule's radius of its axis.
            ASSERT_LE(c.AxisDistance(Apply(m, Vec3{q[0], q[1], q[2]})), c.radius * (1 + 1e-12)) << t << " " << k;
        }
    }
    // A plank turned about z: a capsule along it, as thick as half its cross-section's diagonal.
    const double a = 0.5, turned[4][4] = {{std::cos(a), std::sin(a), 0, 0}, {-std::sin(a), std::cos(a), 0, 0},
                                          {0, 0, 1, 0}, {0, 0, 0, 1}};
    const double lo[3] = {-2, -0.1, -0.2}, hi[3] = {2, 0.1, 0.2};
    const Capsule plank = CapsuleOfBox(lo, hi, turned);
    EXPECT_NEAR(plank.radius, std::sqrt(0.1 * 0.1 + 0.2 * 0.2), 1e-10);
    EXPECT_NEAR(plank.b.x - plank.a.x, 4 * std::cos(a), 1e-10);
}

TEST(ShapeHulls, SphereAndEllipsoidLieInTheirCapsules) {
    std::mt19937_64 rng(10);
    std::uniform_real_distribution<double> u(-1, 1);
    const double centre[3] = {1, -2, 3};
    EXPECT_EQ(CapsuleOfSphere(centre, 2, nullptr).radius, 2);
    for (int t = 0; t < 200; ++t) {
        double m[4][4];
        RandomTransform(rng, m);
        const Capsule c = CapsuleOfSphere(centre, 1.5, &m);
        for (int k = 0; k < 5000; ++k) {
            Vec3 d{u(rng), u(rng), u(rng)};
            const double n = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
            const Vec3 p = Apply(m, Vec3{centre[0] + 1.5 * d.x / n, centre[1] + 1.5 * d.y / n, centre[2] + 1.5 * d.z / n});
            ASSERT_LE(c.AxisDistance(p), c.radius * (1 + 1e-12));
        }
    }
}

TEST(ShapeHulls, ARotatedAndScaledShapeGetsItsOwnRadius) {
    // Rotations and scalings keep the cross-section's axes orthogonal: the capsule is then as
    // thin as the shape (up to rounding), not the sum of the axes' lengths.
    const double a = 0.7, b = -1.1;
    const double rotateThenScale[4][4] = {{0.3 * std::cos(a), 0.3 * std::sin(a), 0, 0},
                                          {-0.3 * std::cos(b) * std::sin(a), 0.3 * std::cos(b) * std::cos(a), 0.3 * std::sin(b), 0},
                                          {0.3 * std::sin(b) * std::sin(a), -0.3 * std::sin(b) * std::cos(a), 0.3 * std::cos(b), 0},
                                          {4, -2, 7, 1}};
    EXPECT_NEAR(CapsuleOfUnitCylinder(rotateThenScale).radius, 0.3, 1e-10);
    const double centre[3] = {1, 2, 3};
    EXPECT_NEAR(CapsuleOfSphere(centre, 2, &rotateThenScale).radius, 0.6, 1e-10);
    // Scaled unevenly, the widest axis counts.
    const double uneven[4][4] = {{2, 0, 0, 0}, {0, 0.5, 0, 0}, {0, 0, 5, 0}, {0, 0, 0, 1}};
    EXPECT_NEAR(CapsuleOfUnitCylinder(uneven).radius, 2, 1e-10);
    // An ellipsoid that uneven runs along its longest axis, as thick as the next one.
    const Capsule ellipsoid = CapsuleOfSphere(centre, 1, &uneven);
    EXPECT_NEAR(ellipsoid.radius, 2, 1e-5);
    EXPECT_NEAR(std::fabs(ellipsoid.b.z - ellipsoid.a.z), 10, 1e-5);
}

}  // namespace
