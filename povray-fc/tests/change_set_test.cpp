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
