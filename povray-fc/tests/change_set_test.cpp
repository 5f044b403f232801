// Tests for ChangeSet and DirtyVoxels: local changes, changes outside the grid, "everything".
#include <limits>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "povrayfc/change_set.h"

using namespace povrayfc;

namespace {
const double kInf = std::numeric_limits<double>::infinity();
const double kNaN = std::numeric_limits<double>::quiet_NaN();
}  // namespace

TEST(ChangeSet, EmptyChangeSetDirtiesNothing) {
    VoxelGrid g(Box{{0, 0, 0}, {4, 4, 4}}, 4, 4, 4);
    ChangeSet cs;
    EXPECT_TRUE(cs.Empty());
    DirtyResult r = DirtyVoxels(g, cs);
    // No change: no dirty voxel and not "all".
    EXPECT_FALSE(r.all);
    EXPECT_EQ(r.voxels.Count(), 0u);
    // The voxel set covers the whole grid.
    EXPECT_EQ(r.voxels.Size(), g.VoxelCount());
}

TEST(ChangeSet, BoxesMarkExactlyTheOverlappedVoxels) {
    VoxelGrid g(Box{{0, 0, 0}, {4, 4, 4}}, 4, 4, 4);
    ChangeSet cs;
    // An object moved from inside voxel (0,0,0) to straddle the face between (2,1,1) and (3,1,1).
    cs.AddBox(Box{{0.2, 0.2, 0.2}, {0.8, 0.8, 0.8}});
    cs.AddBox(Box{{2.5, 1.2, 1.2}, {3.5, 1.8, 1.8}});
    EXPECT_FALSE(cs.Empty());
    DirtyResult r = DirtyVoxels(g, cs);
    EXPECT_FALSE(r.all);
    // Old and new positions are dirty, including both voxels the new box straddles...
    EXPECT_TRUE(r.voxels.Test(g.Index(0, 0, 0)));
    EXPECT_TRUE(r.voxels.Test(g.Index(2, 1, 1)));
    EXPECT_TRUE(r.voxels.Test(g.Index(3, 1, 1)));
    // ...and nothing else.
    EXPECT_EQ(r.voxels.Count(), 3u);
    ChangeSet face;
    face.AddBox(Box{{1, 1, 1}, {1, 1, 1}});
    // A change exactly at an interior grid corner dirties all 8 voxels sharing it.
    EXPECT_EQ(DirtyVoxels(g, face).voxels.Count(), 8u);
}

TEST(ChangeSet, BoxLeavingTheGridMakesEverythingDirty) {
    VoxelGrid g(Box{{0, 0, 0}, {4, 4, 4}}, 4, 4, 4);
    ChangeSet cs;
    cs.AddBox(Box{{1, 1, 1}, {2, 2, 2}});
    cs.AddBox(Box{{3.5, 3.5, 3.5}, {4.5, 4, 4}});  // pokes out through x = 4
    DirtyResult r = DirtyVoxels(g, cs);
    // Rays were only recorded inside the grid, so a change outside it dirties everything.
    EXPECT_TRUE(r.all);
    // All voxels are set too, so a caller looking only at voxels is still conservative.
    EXPECT_EQ(r.voxels.Count(), g.VoxelCount());
    // The reason names the offending box and the grid.
    EXPECT_NE(r.reason.find("not inside the voxel grid"), std::string::npos) << r.reason;
    EXPECT_NE(r.reason.find("4.5"), std::string::npos) << r.reason;

    ChangeSet inf;
    inf.AddBox(Box{{-kInf, 0, -kInf}, {kInf, 0, kInf}});  // an infinite plane changed
    DirtyResult ri = DirtyVoxels(g, inf);
    // An unbounded change dirties everything and says it was unbounded.
    EXPECT_TRUE(ri.all);
    EXPECT_NE(ri.reason.find("unbounded"), std::string::npos) << ri.reason;
    ChangeSet touching;
    touching.AddBox(Box{{0, 0, 0}, {4, 4, 4}});
    // A change touching the grid faces from inside is still local.
    EXPECT_FALSE(DirtyVoxels(g, touching).all);
}

TEST(ChangeSet, MarkAllKeepsFirstReasonAndClearResets) {
    VoxelGrid g(Box{{0, 0, 0}, {1, 1, 1}}, 2, 2, 2);
    ChangeSet cs;
    cs.MarkAll("camera moved");
    cs.MarkAll("light colour changed");
    DirtyResult r = DirtyVoxels(g, cs);
    // MarkAll makes everything dirty with the first reason given.
    EXPECT_TRUE(r.all);
    EXPECT_EQ(r.reason, "camera moved");
    EXPECT_EQ(r.voxels.Count(), 8u);
    cs.Clear();
    // Clear forgets boxes and the "all" mark.
    EXPECT_TRUE(cs.Empty());
    EXPECT_FALSE(DirtyVoxels(g, cs).all);
}

TEST(ChangeSet, RejectsNaNIgnoresEmpty) {
    ChangeSet cs;
    // A NaN box is an upstream bug and is rejected loudly.
    EXPECT_THROW(cs.AddBox(Box{{kNaN, 0, 0}, {1, 1, 1}}), std::invalid_argument);
    // A null reason is rejected.
    EXPECT_THROW(cs.MarkAll(nullptr), std::invalid_argument);
    cs.AddBox(Box{});
    cs.AddBox(Box{{1, 1, 1}, {0, 2, 2}});
    // Empty boxes enclose nothing and are dropped.
    EXPECT_TRUE(cs.Empty());
    EXPECT_TRUE(cs.Boxes().empty());
}

namespace povrayfc {
namespace {

// A thin slanted capsule: its hull marks every voxel a point of the capsule lies in,
// and far fewer voxels than its bounding box.
TEST(ChangeSetCapsule, MarksEveryVoxelTheCapsuleMeetsAndFewerThanItsBox) {
    VoxelGrid grid(Box{Vec3{0, 0, 0}, Vec3{10, 10, 10}}, 20, 20, 20);
    Capsule hull;
    hull.a = Vec3{1.1, 1.3, 2.0};
    hull.b = Vec3{8.7, 9.2, 7.5};
    hull.radius = 0.15;
    Box box{Vec3{1.1 - 0.15, 1.3 - 0.15, 2.0 - 0.15}, Vec3{8.7 + 0.15, 9.2 + 0.15, 7.5 + 0.15}};
    ChangeSet withHull, boxOnly;
    withHull.AddBox(box, hull);
    boxOnly.AddBox(box);
    const DirtyResult tight = DirtyVoxels(grid, withHull), loose = DirtyVoxels(grid, boxOnly);
    ASSERT_FALSE(tight.all);
    // Invariant: points inside the capsule (axis, and offsets up to the radius) are in marked voxels.
    for (int i = 0; i <= 2000; ++i) {
        const double t = i / 2000.0;
        const Vec3 p = hull.a + t * (hull.b - hull.a);
        for (int k = 0; k < 6; ++k) {
            const Vec3 off[6] = {{0.15, 0, 0}, {-0.15, 0, 0}, {0, 0.15, 0}, {0, -0.15, 0}, {0, 0, 0.15}, {0, 0, -0.15}};
            const Vec3 q = p + off[k];
            const int ix = int(q.x / 0.5), iy = int(q.y / 0.5), iz = int(q.z / 0.5);
            EXPECT_TRUE(tight.voxels.Test(grid.Index(ix, iy, iz))) << ix << "," << iy << "," << iz;
        }
    }
    // Invariant: the hull is tighter than the box it refines, and within it.
    EXPECT_LT(tight.voxels.Count() * 4, loose.voxels.Count());
    for (std::uint32_t v = 0; v < grid.VoxelCount(); ++v) {
        if (tight.voxels.Test(v)) {
            EXPECT_TRUE(loose.voxels.Test(v));
        }
    }
}

TEST(ChangeSetCapsule, NaNCapsuleIsRejected) {
    ChangeSet changes;
    Capsule hull;
    hull.radius = kNaN;
    EXPECT_THROW(changes.AddBox(Box{Vec3{0, 0, 0}, Vec3{1, 1, 1}}, hull), std::invalid_argument);
}

}  // namespace
}  // namespace povrayfc
