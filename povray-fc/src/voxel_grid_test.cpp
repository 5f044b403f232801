// Tests for VoxelGrid: validation, padding of degenerate bounds, automatic resolution, box queries.
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "povrayfc/voxel_grid.h"

using namespace povrayfc;

namespace {

const double kInf = std::numeric_limits<double>::infinity();
const double kNaN = std::numeric_limits<double>::quiet_NaN();

std::vector<std::uint32_t> Overlapping(const VoxelGrid &g, const Box &b) {
    std::vector<std::uint32_t> v;
    g.ForEachVoxelOverlapping(b, [&](std::uint32_t i) { v.push_back(i); });
    return v;
}

// Closed cell i on an axis: between the grid's boundaries i and i+1 (the last is the hi face).
void ExactCell(const VoxelGrid &g, int axis, int i, long double &lo, long double &hi) {
    lo = g.Boundary(axis, i);
    hi = (i + 1 == g.Res(axis)) ? g.Bounds().hi[axis] : g.Boundary(axis, i + 1);
}

}  // namespace

TEST(VoxelGrid, IndexLayoutAndCoordsRoundTrip) {
    VoxelGrid g(Box{{0, 0, 0}, {3, 4, 5}}, 3, 4, 5);
    // Index is x + nx*(y + ny*z), the layout the dependency store and change set share.
    EXPECT_EQ(g.Index(0, 0, 0), 0u);
    EXPECT_EQ(g.Index(2, 0, 0), 2u);
    EXPECT_EQ(g.Index(0, 1, 0), 3u);
    EXPECT_EQ(g.Index(1, 2, 3), 1u + 3u * (2u + 4u * 3u));
    EXPECT_EQ(g.VoxelCount(), 60u);
    for (std::uint32_t i = 0; i < g.VoxelCount(); ++i) {
        int x, y, z;
        g.Coords(i, x, y, z);
        // Coords inverts Index for every voxel.
        ASSERT_EQ(g.Index(x, y, z), i);
    }
    int x, y, z;
    // Coords rejects indices past the end instead of inventing coordinates.
    EXPECT_THROW(g.Coords(60, x, y, z), std::invalid_argument);
    Box c = g.VoxelBox(1, 2, 3);
    // VoxelBox is the unit cell at (1,2,3) on this unit-spaced grid.
    EXPECT_DOUBLE_EQ(c.lo.x, 1);
    EXPECT_DOUBLE_EQ(c.hi.y, 3);
    EXPECT_DOUBLE_EQ(c.hi.z, 4);
}

TEST(VoxelGrid, RejectsBadInput) {
    Box ok{{0, 0, 0}, {1, 1, 1}};
    // Non-positive resolutions are rejected.
    EXPECT_THROW(VoxelGrid(ok, 0, 1, 1), std::invalid_argument);
    EXPECT_THROW(VoxelGrid(ok, 1, -3, 1), std::invalid_argument);
    // Resolutions whose product exceeds the voxel limit are rejected.
    EXPECT_THROW(VoxelGrid(ok, 4096, 4096, 4096), std::invalid_argument);
    // NaN, infinite and empty bounds are rejected.
    EXPECT_THROW(VoxelGrid(Box{{kNaN, 0, 0}, {1, 1, 1}}, 1, 1, 1), std::invalid_argument);
    EXPECT_THROW(VoxelGrid(Box{{0, 0, 0}, {1, kInf, 1}}, 1, 1, 1), std::invalid_argument);
    EXPECT_THROW(VoxelGrid(Box{{0, 0, 0}, {1, -1, 1}}, 1, 1, 1), std::invalid_argument);
    EXPECT_THROW(VoxelGrid(Box{}, 1, 1, 1), std::invalid_argument);
    // Finite bounds whose extent overflows are rejected.
    EXPECT_THROW(VoxelGrid(Box{{-1e308, 0, 0}, {1e308, 1, 1}}, 1, 1, 1), std::invalid_argument);
    // Automatic rejects a zero target.
    EXPECT_THROW(VoxelGrid::Automatic(ok, 0), std::invalid_argument);
    try {
        VoxelGrid(Box{{0, 0, 0}, {1, kInf, 1}}, 1, 1, 1);
        FAIL();
    } catch (const std::invalid_argument &e) {
        // The message names the problem so a bad scene bound is easy to find.
        EXPECT_NE(std::string(e.what()).find("finite"), std::string::npos);
    }
}

TEST(VoxelGrid, PadsFlatAndPointBounds) {
    // A disc lying in z = 2: zero extent on z.
    Box disc{{-5, -5, 2}, {5, 5, 2}};
    VoxelGrid g = VoxelGrid::Automatic(disc, 10000);
    const Box &b = g.Bounds();
    // The padded grid still contains the original (flat) bounds.
    EXPECT_TRUE(b.Contains(disc));
    // The flat axis gets a positive width of about 1e-3 of the largest extent.
    EXPECT_GT(b.hi.z - b.lo.z, 0.009);
    EXPECT_LT(b.hi.z - b.lo.z, 0.011);
    // The unpadded axes are unchanged.
    EXPECT_EQ(b.lo.x, -5);
    EXPECT_EQ(b.hi.y, 5);
    // A flat scene gets one layer of voxels and spends the budget on the other axes.
    EXPECT_EQ(g.Res(2), 1);
    EXPECT_EQ(g.Res(0), 100);
    EXPECT_EQ(g.Res(1), 100);

    // A single point (all extents zero) works, at the origin and far from it.
    for (double c : {0.0, 1e7, -3.5}) {
        Box p{{c, c, c}, {c, c, c}};
        VoxelGrid pg = VoxelGrid::Automatic(p, 1000);
        for (int a = 0; a < 3; ++a) {
            // Every padded axis is strictly wider than zero around the point.
            EXPECT_LT(pg.Bounds().lo[a], c);
            EXPECT_GT(pg.Bounds().hi[a], c);
            EXPECT_GT(pg.CellWidth(a), 0);
        }
        std::vector<std::uint32_t> v = Overlapping(pg, p);
        // The point lies in at least one voxel of its own grid.
        EXPECT_FALSE(v.empty());
    }
    Box once = VoxelGrid::PaddedBounds(Box{{1e7, 0, 0}, {1e7, 0, 0}});
    Box twice = VoxelGrid::PaddedBounds(once);
    // Padding is idempotent, so a grid rebuilt from another grid's bounds is the same grid.
    for (int a = 0; a < 3; ++a) {
        EXPECT_EQ(once.lo[a], twice.lo[a]);
        EXPECT_EQ(once.hi[a], twice.hi[a]);
    }
}

TEST(VoxelGrid, AutomaticGivesCubicVoxelsNearTarget) {
    struct Case {
        Box b;
        std::size_t target;
    } cases[] = {
        {{{0, 0, 0}, {1, 1, 1}}, 1000},
        {{{-10, -2, 0}, {10, 2, 5}}, 262144},
        {{{0, 0, 0}, {1e-6, 2e-6, 1e-6}}, 50000},
        {{{-1e7, -1e7, -1e7}, {1e7, 1e7, 5e6}}, 100000},
        {{{0, 0, 0}, {3, 1, 1}}, 1},
    };
    for (const Case &c : cases) {
        VoxelGrid g = VoxelGrid::Automatic(c.b, c.target);
        double total = double(g.VoxelCount());
        // Total voxel count is within a factor 2 of the target.
        EXPECT_GE(total, 0.5 * c.target);
        EXPECT_LE(total, 2.0 * c.target + 3);
        if (c.target > 1) {
            double wmin = std::min({g.CellWidth(0), g.CellWidth(1), g.CellWidth(2)});
            double wmax = std::max({g.CellWidth(0), g.CellWidth(1), g.CellWidth(2)});
            // Voxels are roughly cubic (side ratio under 1.5) when no axis is pinned.
            EXPECT_LT(wmax / wmin, 1.5) << ToString(c.b);
        }
    }
    // A needle-like scene pins the long axis at the cap and spreads the rest.
    VoxelGrid needle = VoxelGrid::Automatic(Box{{0, 0, 0}, {1000, 1, 1}}, 1000000);
    EXPECT_EQ(needle.Res(0), VoxelGrid::kMaxAutomaticResolution);
    EXPECT_GE(double(needle.VoxelCount()), 0.5e6);
    EXPECT_LE(double(needle.VoxelCount()), 2e6);
    // A gigantic target is capped at kMaxAutomaticResolution per axis.
    VoxelGrid huge = VoxelGrid::Automatic(Box{{0, 0, 0}, {1, 1, 1}}, std::size_t(1) << 40);
    for (int a = 0; a < 3; ++a) EXPECT_EQ(huge.Res(a), VoxelGrid::kMaxAutomaticResolution);
}

TEST(VoxelGrid, BoxOnCellFaceTouchesBothSides) {
    VoxelGrid g(Box{{0, 0, 0}, {4, 4, 4}}, 4, 4, 4);
    // A box that is exactly the face x = 2 between cells 1 and 2 touches both closed cells.
    std::vector<std::uint32_t> v = Overlapping(g, Box{{2, 0.5, 0.5}, {2, 0.5, 0.5}});
    std::vector<std::uint32_t> want = {g.Index(1, 0, 0), g.Index(2, 0, 0)};
    EXPECT_EQ(v, want);
    // A point on a grid-interior corner touches all 8 cells around it.
    EXPECT_EQ(Overlapping(g, Box{{1, 1, 1}, {1, 1, 1}}).size(), 8u);
    // A box strictly inside one cell touches only that cell.
    EXPECT_EQ(Overlapping(g, Box{{1.2, 1.2, 1.2}, {1.8, 1.8, 1.8}}),
              std::vector<std::uint32_t>{g.Index(1, 1, 1)});
}

TEST(VoxelGrid, BoxesPartlyOrWhollyOutside) {
    VoxelGrid g(Box{{0, 0, 0}, {4, 4, 4}}, 4, 4, 4);
    Box partly{{-10, 3.5, 3.5}, {0.5, 10, 10}};
    // A box partly outside covers only the inside part...
    EXPECT_EQ(Overlapping(g, partly), std::vector<std::uint32_t>{g.Index(0, 3, 3)});
    // ...and BoxInside tells the caller something changed outside the grid.
    EXPECT_FALSE(g.BoxInside(partly));
    // A box wholly outside covers nothing.
    EXPECT_TRUE(Overlapping(g, Box{{5, 0, 0}, {6, 1, 1}}).empty());
    // An infinite box covers the whole grid and is not inside.
    Box all{{-kInf, -kInf, -kInf}, {kInf, kInf, kInf}};
    EXPECT_EQ(Overlapping(g, all).size(), g.VoxelCount());
    EXPECT_FALSE(g.BoxInside(all));
    // NaN and empty boxes cover nothing; NaN is never "inside".
    EXPECT_TRUE(Overlapping(g, Box{{kNaN, 0, 0}, {1, 1, 1}}).empty());
    EXPECT_FALSE(g.BoxInside(Box{{kNaN, 0, 0}, {1, 1, 1}}));
    EXPECT_TRUE(Overlapping(g, Box{}).empty());
    // Touching the grid's own faces still counts as inside.
    EXPECT_TRUE(g.BoxInside(Box{{0, 0, 0}, {4, 4, 4}}));
    // A box touching the outside of the grid face from outside covers the boundary layer.
    EXPECT_EQ(Overlapping(g, Box{{4, 0.5, 0.5}, {9, 0.5, 0.5}}),
              std::vector<std::uint32_t>{g.Index(3, 0, 0)});
}

TEST(VoxelGrid, OverlapMatchesBruteForceOnRandomBoxes) {
    std::mt19937_64 rng(12345);
    std::uniform_real_distribution<double> u(0, 1);
    std::size_t extras = 0, exact = 0;
    for (int iter = 0; iter < 3000; ++iter) {
        double scale = std::pow(10.0, -6 + 13 * u(rng));
        Vec3 lo{scale * (u(rng) - 0.5) * 6, scale * (u(rng) - 0.5) * 6, scale * (u(rng) - 0.5) * 6};
        Vec3 hi = lo + scale * Vec3{0.2 + u(rng), 0.2 + u(rng), 0.2 + u(rng)};
        VoxelGrid g(Box{lo, hi}, 1 + int(u(rng) * 9), 1 + int(u(rng) * 9), 1 + int(u(rng) * 9));
        auto coord = [&](int a) {
            // Half the time exactly on a cell boundary, to exercise closed-face handling.
            if (u(rng) < 0.5) return g.Boundary(a, int(u(rng) * (g.Res(a) + 1)));
            return g.Bounds().lo[a] - 0.3 * scale + u(rng) * (hi[a] - lo[a] + 0.6 * scale);
        };
        Box q;
        q.Grow(Vec3{coord(0), coord(1), coord(2)});
        q.Grow(Vec3{coord(0), coord(1), coord(2)});
        std::vector<std::uint32_t> got = Overlapping(g, q);
        std::set<std::uint32_t> gotSet(got.begin(), got.end());
        // Every voxel is visited at most once.
        ASSERT_EQ(gotSet.size(), got.size());
        for (int z = 0; z < g.Res(2); ++z)
            for (int y = 0; y < g.Res(1); ++y)
                for (int x = 0; x < g.Res(0); ++x) {
                    int i[3] = {x, y, z};
                    bool touches = true, near = true;
                    for (int a = 0; a < 3; ++a) {
                        long double clo, chi;
                        ExactCell(g, a, i[a], clo, chi);
                        long double tol = 1e-6L * (chi - clo);
                        touches &= q.lo[a] <= chi && clo <= q.hi[a];
                        near &= q.lo[a] <= chi + tol && clo - tol <= q.hi[a];
                    }
                    bool in = gotSet.count(g.Index(x, y, z)) != 0;
                    exact += touches;
                    extras += in && !touches;
                    if (touches) {
                        // Conservative: every voxel whose closed cell meets the box is visited.
                        ASSERT_TRUE(in) << iter << " voxel " << x << "," << y << "," << z;
                    }
                    if (in) {
                        // Not wildly over-inclusive: extras lie within 1e-6 cell of the box.
                        ASSERT_TRUE(near) << iter << " voxel " << x << "," << y << "," << z;
                    }
                }
    }
    // Extras are rare (they need a face within ~1e-7 cell of the box).
    EXPECT_LT(double(extras), 0.01 * double(exact));
}
