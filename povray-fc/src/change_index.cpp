// ChangeIndex: union-box rejection, direct hull tests, and the voxel grid for many hulls.
#include "povrayfc/change_index.h"

#include <algorithm>

#include "povrayfc/segment_walker.h"

namespace povrayfc {

namespace {

Vec3 Centre(const Box &b) { return 0.5 * (b.lo + b.hi); }
double HalfExtent(const Box &b) {
    const Vec3 e = b.Extent();
    return 0.5 * std::max({e.x, e.y, e.z});
}

// About this many voxels per hull: enough that a voxel holds a few hulls.
constexpr std::size_t kVoxelsPerHull = 8;
constexpr std::size_t kMaxGridVoxels = std::size_t(1) << 18;

}  // namespace

ChangeIndex::ChangeIndex(std::vector<Hull> hulls, int gridResolution) {
    for (Hull &h : hulls)
        if (!h.box.Empty()) hulls_.push_back(std::move(h));
    for (const Hull &h : hulls_) bounds_.Grow(h.box);
    for (const Hull &h : hulls_) tests_.push_back(PrepareHullTest(h));
    boundsFinite_ = bounds_.IsFinite();
    if (!hulls_.empty() && bounds_.IsFinite()) {
        boundsCentre_ = Centre(bounds_);
        boundsHalfExtent_ = HalfExtent(bounds_);
    }
    if (hulls_.size() <= kDirectHulls || !bounds_.IsFinite()) return;

    // Hulls are binned widened by a slack; a segment whose own rounding margin could be
    // larger (an origin very far from the change) skips the grid and tests every hull.
    gridSlack_ = 0x1p-8 * std::max(HalfExtent(bounds_), 1e-30) + 0x1p-20 * std::max({std::fabs(bounds_.lo.x),
        std::fabs(bounds_.lo.y), std::fabs(bounds_.lo.z), std::fabs(bounds_.hi.x), std::fabs(bounds_.hi.y),
        std::fabs(bounds_.hi.z)});
    const Vec3 slack{gridSlack_, gridSlack_, gridSlack_};
    const Box gridBox{bounds_.lo - slack, bounds_.hi + slack};
    if (gridResolution > 0) {
        const Vec3 e = gridBox.Extent();
        const double longest = std::max({e.x, e.y, e.z});
        int n[3];
        for (int a = 0; a < 3; ++a) n[a] = std::max(1, int(std::ceil(gridResolution * e[a] / longest)));
        grid_ = std::make_unique<VoxelGrid>(gridBox, n[0], n[1], n[2]);
    } else {
        grid_ = std::make_unique<VoxelGrid>(
            VoxelGrid::Automatic(gridBox, std::min(kMaxGridVoxels, hulls_.size() * kVoxelsPerHull)));
    }

    // Two passes (count, fill) into a compressed row layout: no per-voxel vectors.
    const std::size_t voxels = grid_->VoxelCount();
    cellStart_.assign(voxels + 1, 0);
    auto widened = [&](const Hull &h) { return Box{h.box.lo - slack, h.box.hi + slack}; };
    for (const Hull &h : hulls_) grid_->ForEachVoxelOverlapping(widened(h), [&](std::uint32_t v) { ++cellStart_[v + 1]; });
    for (std::size_t v = 0; v < voxels; ++v) cellStart_[v + 1] += cellStart_[v];
    cellHulls_.resize(cellStart_[voxels]);
    std::vector<std::uint32_t> fill(cellStart_.begin(), cellStart_.end() - 1);
    for (std::uint32_t i = 0; i < hulls_.size(); ++i)
        grid_->ForEachVoxelOverlapping(widened(hulls_[i]), [&](std::uint32_t v) { cellHulls_[fill[v]++] = i; });
}

bool ChangeIndex::MayMeet(const Segment &s) const {
    if (hulls_.empty()) return false;
    if (!boundsFinite_) return true;
    // A hull inside the union has a margin at most twice the union's (max norm), so the
    // union widened by twice its own margin holds every hull widened by its margin.
    const double margin = 2.0 * SegmentMargin(s, boundsCentre_, boundsHalfExtent_);
    if (!MeetsWidened(s, bounds_, margin)) return false;
    if (grid_ && margin <= gridSlack_) return MayMeetThroughGrid(s);
    for (std::size_t i = 0; i < hulls_.size(); ++i)
        if (MayMeetHull(s, i)) return true;
    return false;
}

double ChangeIndex::UnionClearance(const Segment &s) const {
    if (hulls_.empty() || !boundsFinite_) return 0.0;
    // The largest clearance worth knowing: a change that moves farther than its own size
    // from one frame to a later one is tested again anyway.
    const double cap = 2.0 * boundsHalfExtent_ + 1e-30;
    return ClearanceWidened(s, bounds_, 4.0 * SegmentMargin(s, boundsCentre_, boundsHalfExtent_), cap);
}

bool ChangeIndex::MayMeetThroughGrid(const Segment &s) const {
    // Where the true ray meets a hull, the stored one passes within its margin (< slack),
    // so inside that hull's widened box: in a voxel the hull was binned into.
    SegmentWalker walker(*grid_, Vec3{s.origin[0], s.origin[1], s.origin[2]},
                         Vec3{s.direction[0], s.direction[1], s.direction[2]}, 0.0, double(s.length));
    if (!walker.Valid()) return true;
    std::uint32_t v;
    while (walker.Next(v)) {
        for (std::uint32_t k = cellStart_[v]; k < cellStart_[v + 1]; ++k)
            if (MayMeetHull(s, cellHulls_[k])) return true;
    }
    return false;
}

}  // namespace povrayfc
