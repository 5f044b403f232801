// Tests for ChangeIndex: the voxel-grid path for many hulls answers like testing every hull.
#include <random>

#include <gtest/gtest.h>

#include "povrayfc/change_index.h"

using namespace povrayfc;

namespace {

Segment Seg(Vec3 o, Vec3 d, double t) {
    const double od[3] = {o.x, o.y, o.z}, dd[3] = {d.x, d.y, d.z};
    Segment s;
    MakeSegment(od, dd, t, s);
    return s;
}

TEST(ChangeIndex, EmptyMeetsNothing) {
    ChangeIndex none;
    EXPECT_TRUE(none.Empty());
    EXPECT_FALSE(none.MayMeet(Seg({0, 0, 0}, {1, 0, 0}, 1e30)));
}

TEST(ChangeIndex, FewHullsAreTestedDirectly) {
    ChangeIndex index({MakeHull(Box{Vec3{0, 0, 0}, Vec3{1, 1, 1}}), MakeHull(Box{Vec3{5, 0, 0}, Vec3{6, 1, 1}})});
    EXPECT_FALSE(index.HasGrid());
    EXPECT_TRUE(index.MayMeet(Seg({5.5, 0.5, -3}, {0, 0, 1}, 10)));
    EXPECT_FALSE(index.MayMeet(Seg({3, 0.5, -3}, {0, 0, 1}, 10)));  // between the two
}

TEST(ChangeIndex, GridAnswersLikeEveryHull) {
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> pos(-10, 10), size(0.05, 1.5), dir(-1, 1);
    std::vector<Hull> hulls;
    for (int i = 0; i < 400; ++i) {
        Vec3 lo{pos(rng), pos(rng), pos(rng)};
        Box b{lo, lo + Vec3{size(rng), size(rng), size(rng)}};
        if (i % 3 == 0) {
            Capsule c;
            c.a = 0.5 * (b.lo + b.hi);
            c.b = c.a;
            c.radius = 0.5 * size(rng);
            hulls.push_back(MakeHull(b, c));
        } else {
            hulls.push_back(MakeHull(b));
        }
    }
    ChangeIndex index(hulls);
    ASSERT_TRUE(index.HasGrid());
    int hits = 0, misses = 0;
    for (int i = 0; i < 50000; ++i) {
        Vec3 o{3 * pos(rng), 3 * pos(rng), 3 * pos(rng)};
        if (i % 4 == 0) o = Vec3{pos(rng), pos(rng), pos(rng)};  // inside the changed region
        Vec3 d{dir(rng), dir(rng), dir(rng)};
        const double t = (i % 2) ? 1e30 : 20 * (0.5 + 0.5 * dir(rng));
        const Segment s = Seg(o, d, t);
        bool any = false;
        for (const Hull &h : hulls) any = any || MayMeet(s, h);
        // Invariant: the grid never misses a hull that the direct test finds.
        if (any) {
            ++hits;
            ASSERT_TRUE(index.MayMeet(s)) << i;
        } else {
            ++misses;
            EXPECT_FALSE(index.MayMeet(s)) << i;
        }
    }
    EXPECT_GT(hits, 1000);
    EXPECT_GT(misses, 1000);
}

TEST(ChangeIndex, FarOriginsFallBackToEveryHull) {
    std::vector<Hull> hulls;
    for (int i = 0; i < 40; ++i) hulls.push_back(MakeHull(Box{Vec3{double(i), 0, 0}, Vec3{i + 0.5, 0.5, 0.5}}));
    ChangeIndex index(hulls);
    ASSERT_TRUE(index.HasGrid());
    // A ray from a million units away, aimed at hull 7's centre.
    const Vec3 target{7.25, 0.25, 0.25}, o{7.25, 0.25, -1e6};
    EXPECT_TRUE(index.MayMeet(Seg(o, target - o, 2.0)));
}

}  // namespace
