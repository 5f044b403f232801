// Conservative 3D-DDA: enumerates every voxel a ray segment touches, without allocating.
#ifndef POVRAYFC_SEGMENT_WALKER_H
#define POVRAYFC_SEGMENT_WALKER_H

#include <cassert>
#include <cstdint>
#include <limits>

#include "povrayfc/geometry.h"
#include "povrayfc/voxel_grid.h"

namespace povrayfc {

// SegmentWalker yields each voxel whose closed cell the segment
//     { origin + t*dir : tmin <= t <= tmax }
// touches, exactly once, clipped to the grid. It may also yield a voxel that passes within
// about Margin(axis) (~1e-7 of a cell) of the segment, never miss one: povray-fc re-uses a
// pixel only if none of the voxels its rays touched changed, so a missed voxel is a wrong
// image while an extra one only costs a re-trace.
//
// How it stays conservative. Like pbrt's DDAMajorantIterator it keeps, per axis, a step
// (+1, -1, or 0 for a zero direction component; -0 is normalised to 0) and the t of the
// next boundary crossing, all set up in the constructor. Unlike a classic DDA it does not
// keep one current cell per axis but a range [first, last] of the cells whose interval,
// enlarged by the margin, contains the current position. Each moving axis has two events:
// "enter" (the next cell's enlarged interval is reached: the range grows) and "leave" (the
// position passes the trailing cell's enlarged interval: the range shrinks). Events are
// processed in t order, enters first on ties. On every enter the new slab of voxels (new
// cell on that axis x current ranges of the others) is yielded; at the start the whole
// product of ranges is. A voxel is therefore yielded exactly when its enlarged cell meets
// the segment, and once, because that happens over one t interval.
// So a segment through an edge or corner yields all 4 or 8 voxels that share it, a segment
// lying in a face between voxels yields both sides for its whole length, and a zero-length
// segment yields every voxel whose closed cell contains the point.
//
// Fast path. Away from edges and corners every range is one cell, and an enter on axis a
// is followed by the leave of a's previous cell before any other event; Next() then does
// both at once, which is a classic DDA step (3-way minimum, one voxel). Everything else
// (ranges of two cells, near-ties between axes) goes through the general event loop.
//
// Precision. Event times are computed directly as (boundary -+ margin - p0) / dir, never
// accumulated, so error does not grow along the ray. p0 is the clipped entry point; its
// rounding (a few ulps of |origin|) is added to the margin, as is the rounding of the
// boundaries (see VoxelGrid::Margin), so a far-away origin or huge t costs over-inclusion
// of a hair, not a miss. The "one past the end" sentinel of a classic DDA is the +infinity
// enter time of an axis whose range already reaches the grid edge; the walk ends when a
// leave would empty a range (the segment left the grid) or the next event is beyond tEnd.
//
// Input rules (the walker never throws: it sits in the innermost ray loop):
//  - dir need not be normalised; t is in units of dir. Any finite magnitude works (a dir
//    whose largest component is beyond 2^+-400 is rescaled by a power of two, exactly).
//  - tmin/tmax may be +-infinity (an unbounded ray: POV-Ray's BOUND_HUGE = 2e10 works too).
//  - tmin > tmax is an empty segment: Valid(), yields nothing.
//  - dir == (0,0,0) is the single point origin, whatever tmin/tmax (a segment that does not
//    move touches only the voxels containing its point).
//  - NaN in origin, dir, tmin or tmax, or an infinite origin or dir component: Valid() is
//    false and nothing is yielded. Such a ray's voxels are unknown, so a caller recording
//    dependencies must not treat "nothing yielded" as "depends on nothing"; see
//    PixelRecorder::MarkEverything().
class SegmentWalker {
  public:
    SegmentWalker(const VoxelGrid &grid, Vec3 origin, Vec3 dir, double tmin, double tmax);

    // False when the input was rejected (NaN or non-finite origin/dir); see class comment.
    bool Valid() const { return valid_; }

    // Stores the next voxel index and returns true, or returns false when done.
    bool Next(std::uint32_t &voxel) {
        if (emitting_) return Emit(voxel);
        if (done_) return false;
        if (first_[0] == last_[0] && first_[1] == last_[1] && first_[2] == last_[2]) {
            // Fast path: the next event is an enter (single-cell ranges enter before they
            // leave); if the same axis' leave comes before every other axis' events, do
            // both: the segment moves from one voxel to the next, touching nothing else.
            // Branch-free axis choice (pbrt's comparison table): which axis is next is
            // random for a random ray, so a branch would mispredict every other step.
            static constexpr int kCmpToAxis[8] = {2, 1, 2, 1, 2, 2, 0, 0};
            static constexpr int kOther1[3] = {1, 2, 0}, kOther2[3] = {2, 0, 1};
            const int bits = ((enterT_[0] < enterT_[1]) << 2) + ((enterT_[0] < enterT_[2]) << 1) +
                             (enterT_[1] < enterT_[2]);
            const int a = kCmpToAxis[bits], b = kOther1[a], c = kOther2[a];
            const double tl = leaveT_[a];
            // Non-short-circuit &: one well-predicted branch instead of five.
            if ((enterT_[a] <= tEnd_) & (tl < enterT_[b]) & (tl < enterT_[c]) & (tl < leaveT_[b]) &
                (tl < leaveT_[c])) {
                first_[a] = last_[a] = first_[a] + step_[a];
                enterK_[a] += step_[a];
                leaveK_[a] += step_[a];
                const double te = EventT(a, enterBase_[a], enterK_[a]);
                enterT_[a] = enterK_[a] == enterStop_[a] ? kInf : te;
                leaveT_[a] = EventT(a, leaveBase_[a], leaveK_[a]);
                voxel = std::uint32_t(first_[0]) + nx_ * std::uint32_t(first_[1]) +
                        nxy_ * std::uint32_t(first_[2]);
                return true;
            }
        }
        return SlowNext(voxel);
    }

  private:
    static constexpr double kInf = std::numeric_limits<double>::infinity();

    // t at which the segment reaches boundary k shifted by the margin, i.e.
    // (lo + k*w -+ margin - p0) / dir with the constant part precomputed in `base`.
    double EventT(int axis, double base, int k) const {
        return (base + k * grid_->CellWidth(axis)) * invDir_[axis];
    }

    // Yields the next voxel of the pending slab [emitFirst_, emitLast_].
    bool Emit(std::uint32_t &voxel) {
        voxel = std::uint32_t(cur_[0]) + nx_ * std::uint32_t(cur_[1]) + nxy_ * std::uint32_t(cur_[2]);
        if (++cur_[0] > emitLast_[0]) {
            cur_[0] = emitFirst_[0];
            if (++cur_[1] > emitLast_[1]) {
                cur_[1] = emitFirst_[1];
                if (++cur_[2] > emitLast_[2]) emitting_ = false;
            }
        }
        return true;
    }

    // General event loop: ranges wider than one cell, near-ties between axes, the end.
    bool SlowNext(std::uint32_t &voxel);
    // Processes the earliest pending event; sets emitting_ (a new slab to yield) or done_,
    // or neither (a leave, which yields nothing).
    void Advance();

    const VoxelGrid *grid_;
    std::uint32_t nx_ = 0, nxy_ = 0;
    int res_[3] = {0, 0, 0};
    int step_[3] = {0, 0, 0};
    int first_[3] = {0, 0, 0}, last_[3] = {0, 0, 0};  // current inclusive cell range per axis
    double p0_[3] = {0, 0, 0};                         // clipped entry point (t = 0 from here)
    double dir_[3] = {0, 0, 0};                        // dir scaled by a power of two
    double invDir_[3] = {0, 0, 0};
    double margin_[3] = {0, 0, 0};
    double enterBase_[3] = {0, 0, 0}, leaveBase_[3] = {0, 0, 0};
    // Boundary index of the next enter / leave event per axis; both move by step_ per
    // event. enterStop_ is the one-past-the-end boundary: no cell to enter there.
    int enterK_[3] = {0, 0, 0}, leaveK_[3] = {0, 0, 0}, enterStop_[3] = {0, 0, 0};
    double enterT_[3] = {kInf, kInf, kInf}, leaveT_[3] = {kInf, kInf, kInf};
    double tEnd_ = 0;  // clipped segment end, relative to p0
    int emitFirst_[3] = {0, 0, 0}, emitLast_[3] = {0, 0, 0}, cur_[3] = {0, 0, 0};
    bool emitting_ = false;
    bool done_ = true;
    bool valid_ = false;
};

// Calls f(uint32_t voxel) for every voxel the segment touches (see SegmentWalker).
// Returns SegmentWalker::Valid(): false means the input had NaN/inf and nothing was visited.
template <class F>
bool WalkSegment(const VoxelGrid &grid, Vec3 origin, Vec3 dir, double tmin, double tmax, F f) {
    SegmentWalker walker(grid, origin, dir, tmin, tmax);
    std::uint32_t voxel;
    while (walker.Next(voxel)) f(voxel);
    return walker.Valid();
}

}  // namespace povrayfc

#endif
