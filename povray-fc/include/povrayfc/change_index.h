// ChangeIndex: the hulls that changed this frame, and the question every stored sample
// asks at the start of a frame: may one of my ray segments meet a change?
#ifndef POVRAYFC_CHANGE_INDEX_H
#define POVRAYFC_CHANGE_INDEX_H

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "povrayfc/hull.h"
#include "povrayfc/segment.h"
#include "povrayfc/voxel_grid.h"

namespace povrayfc {

// Immutable once built, so the render threads query it concurrently.
//
// Every segment is first tested against the box around all changed hulls, which rejects
// most segments of a local change in a few nanoseconds. Segments that pass test the
// hulls directly while there are few of them; with many (a scene where hundreds of
// small objects move) the hulls are binned into a uniform voxel grid over their union,
// and the segment is walked through it with the conservative 3D-DDA, testing only the
// hulls of the voxels it crosses: the paper's grid and walk, spent only on the rays that
// pass near a change, once per frame, instead of on every ray at the time it is traced.
class ChangeIndex {
  public:
    // More hulls than this get the grid.
    static constexpr std::size_t kDirectHulls = 12;

    ChangeIndex() = default;  // nothing changed
    // gridResolution: cells along the union's longest axis for many hulls; 0 = automatic.
    explicit ChangeIndex(std::vector<Hull> hulls, int gridResolution = 0);

    bool Empty() const { return hulls_.empty(); }
    std::size_t HullCount() const { return hulls_.size(); }
    const std::vector<Hull> &Hulls() const { return hulls_; }
    const Box &Bounds() const { return bounds_; }
    bool HasGrid() const { return grid_ != nullptr; }

    // True when the ray the segment stands for may meet a changed hull.
    bool MayMeet(const Segment &s) const;
    // The cheap first test, against the box around all changed hulls: 0 when the segment
    // may meet it; else how much farther out than the segment's margin that box could reach
    // with the segment still missing it (at most twice the box's half extent). The margin is
    // twice the one a hull inside the box needs (MayMeet's), so that the rounding of this
    // test and of a later frame's is covered too (change_drift.h).
    double UnionClearance(const Segment &s) const;
    // True when it may meet changed hull i (MayMeet(s, Hulls()[i]), prepared once).
    bool MayMeetHull(const Segment &s, std::size_t i) const { return povrayfc::MayMeet(s, hulls_[i], tests_[i]); }

  private:
    bool MayMeetThroughGrid(const Segment &s) const;

    std::vector<Hull> hulls_;
    std::vector<HullTest> tests_;  // per hull
    Box bounds_;  // union of the hull boxes
    bool boundsFinite_ = true;
    // Its centre and half extent (max norm), for every segment's margin: worked out once.
    Vec3 boundsCentre_{0.0, 0.0, 0.0};
    double boundsHalfExtent_ = 0.0;
    std::unique_ptr<VoxelGrid> grid_;
    double gridSlack_ = 0.0;               // hulls are binned widened by this much
    std::vector<std::uint32_t> cellStart_;  // CSR: hulls of voxel v are
    std::vector<std::uint32_t> cellHulls_;  // cellHulls_[cellStart_[v] .. cellStart_[v+1])
};

}  // namespace povrayfc

#endif
