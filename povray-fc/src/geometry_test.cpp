// Tests for Vec3/Box helpers: emptiness, growing, closed containment and overlap.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "povrayfc/geometry.h"

using namespace povrayfc;

TEST(Geometry, DefaultBoxIsEmptyAndGrowsFromNothing) {
    Box b;
    // A default box must be empty so Grow starts from nothing, not from the origin.
    EXPECT_TRUE(b.Empty());
    b.Grow(Vec3{1, 2, 3});
    // One point gives a degenerate but non-empty box.
    EXPECT_FALSE(b.Empty());
    EXPECT_EQ(b.lo.x, 1);
    EXPECT_EQ(b.hi.z, 3);
    b.Grow(Vec3{-1, 5, 0});
    // Growing takes per-axis min and max.
    EXPECT_EQ(b.lo.x, -1);
    EXPECT_EQ(b.lo.z, 0);
    EXPECT_EQ(b.hi.y, 5);
    EXPECT_EQ(b.hi.x, 1);
}

TEST(Geometry, EmptinessAndNaN) {
    // lo > hi on any single axis makes the box empty.
    EXPECT_TRUE((Box{{0, 0, 0}, {1, -1, 1}}).Empty());
    EXPECT_FALSE((Box{{0, 0, 0}, {0, 0, 0}}).Empty());
    const double nan = std::numeric_limits<double>::quiet_NaN();
    Box n{{0, nan, 0}, {1, 1, 1}};
    // A NaN box reports both HasNaN and Empty so nothing iterates it by accident.
    EXPECT_TRUE(n.HasNaN());
    EXPECT_TRUE(n.Empty());
    const double inf = std::numeric_limits<double>::infinity();
    // Infinite boxes are not finite but also not empty.
    EXPECT_FALSE((Box{{-inf, 0, 0}, {1, 1, 1}}).IsFinite());
    EXPECT_FALSE((Box{{-inf, 0, 0}, {1, 1, 1}}).Empty());
}

TEST(Geometry, UnionIgnoresEmptyBoxes) {
    Box a{{0, 0, 0}, {1, 1, 1}};
    Box u = Union(a, Box{});
    // The union with an empty box is the box itself.
    EXPECT_EQ(u.lo.x, 0);
    EXPECT_EQ(u.hi.x, 1);
    Box v = Union(a, Box{{2, -1, 0.5}, {3, 0, 0.5}});
    // Union spans both boxes on every axis.
    EXPECT_EQ(v.lo.y, -1);
    EXPECT_EQ(v.hi.x, 3);
    EXPECT_EQ(v.hi.z, 1);
}

TEST(Geometry, ClosedContainmentAndOverlap) {
    Box a{{0, 0, 0}, {1, 1, 1}};
    // Points on faces, edges and corners are inside a closed box.
    EXPECT_TRUE(a.Contains(Vec3{1, 1, 1}));
    EXPECT_TRUE(a.Contains(Vec3{0, 0.5, 1}));
    EXPECT_FALSE(a.Contains(Vec3{1.0000001, 0.5, 0.5}));
    // Boxes sharing only a corner overlap (closed sets).
    EXPECT_TRUE(a.Overlaps(Box{{1, 1, 1}, {2, 2, 2}}));
    EXPECT_FALSE(a.Overlaps(Box{{1.5, 0, 0}, {2, 1, 1}}));
    // A box with a shared face is contained; one poking out is not.
    EXPECT_TRUE(a.Contains(Box{{0, 0, 0}, {1, 0.5, 1}}));
    EXPECT_FALSE(a.Contains(Box{{0, 0, 0}, {1, 0.5, 1.5}}));
    Box i = Intersection(a, Box{{0.5, -1, 0.25}, {3, 0.75, 0.5}});
    // The intersection is the common part per axis.
    EXPECT_EQ(i.lo.x, 0.5);
    EXPECT_EQ(i.hi.y, 0.75);
    EXPECT_EQ(i.lo.z, 0.25);
    // Disjoint boxes intersect in an empty box.
    EXPECT_TRUE(Intersection(a, Box{{2, 2, 2}, {3, 3, 3}}).Empty());
}

TEST(Geometry, IndexingAndToString) {
    Vec3 v{1, 2, 3};
    v[1] = 7;
    // operator[] maps 0,1,2 to x,y,z for reading and writing.
    EXPECT_EQ(v.y, 7);
    EXPECT_EQ(v[2], 3);
    // ToString prints round-trippable numbers for error messages.
    EXPECT_EQ(ToString(Vec3{0.1, -2, 3}), "(0.10000000000000001, -2, 3)");
}
