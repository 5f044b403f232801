// SegmentWalker set-up: input checks, clipping to the grid and the first event per axis.
#include "povrayfc/segment_walker.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

namespace povrayfc {

SegmentWalker::SegmentWalker(const VoxelGrid &grid, Vec3 origin, Vec3 dir, double tmin, double tmax)
    : grid_(&grid) {
    if (std::isnan(tmin) || std::isnan(tmax) || !origin.IsFinite() || !dir.IsFinite()) return;
    valid_ = true;
    if (tmin > tmax) return;  // empty segment

    nx_ = std::uint32_t(grid.Res(0));
    nxy_ = nx_ * std::uint32_t(grid.Res(1));
    const Box &bounds = grid.Bounds();

    // 1/dir is used for event times; it must stay finite, so a component below 2^-600 of
    // the largest gets no events ("slow" axis). That is safe: within the clipped segment,
    // at most about one grid diagonal long along the largest component, such an axis moves
    // by < 1e-180 of the grid size, far inside the margin the start range already covers.
    // (It still moves in the clip and in p0: from a far origin the drift adds up.) Kept
    // components have 1/dir <= 2^1000 as long as the largest is in [2^-400, 2^400];
    // outside that (rare) range dir is first scaled by a power of two, exactly, and t by
    // the inverse.
    double maxAbs = std::max({std::fabs(dir.x), std::fabs(dir.y), std::fabs(dir.z)});
    const bool moving = maxAbs > 0;
    bool slow[3] = {false, false, false};
    if (moving) {
        double d[3] = {dir.x, dir.y, dir.z};
        if (!(maxAbs >= 0x1p-400 && maxAbs <= 0x1p400)) {
            int e = std::ilogb(maxAbs);
            for (int a = 0; a < 3; ++a) d[a] = std::ldexp(d[a], -e);
            tmin = std::ldexp(tmin, e);
            tmax = std::ldexp(tmax, e);
            maxAbs = std::ldexp(maxAbs, -e);
        }
        const double tiny = maxAbs * 0x1p-600;
        for (int a = 0; a < 3; ++a) {
            dir_[a] = d[a] + 0.0;  // -0 + 0 == +0: a zero component never picks a step sign
            slow[a] = std::fabs(d[a]) < tiny;
        }
    }
    for (int a = 0; a < 3; ++a) {
        res_[a] = grid.Res(a);
        // p0 below is a few ulps of |origin| off the true ray; widen the margin by that
        // so a ray from far away cannot slip past a boundary.
        margin_[a] = grid.Margin(a) + 32 * DBL_EPSILON * std::fabs(origin[a]);
    }

    double t0 = tmin, t1 = tmax;
    if (moving) {
        // Slab clip against the grid enlarged by the margin.
        for (int a = 0; a < 3; ++a) {
            double lo = bounds.lo[a] - margin_[a], hi = bounds.hi[a] + margin_[a];
            if (dir_[a] == 0) {
                if (origin[a] < lo || origin[a] > hi) return;  // parallel and outside
                continue;
            }
            double ta, tb;
            if (slow[a]) {
                // Divide (x / tiny is +-inf at worst, never NaN like 0 * inf could be).
                ta = (lo - origin[a]) / dir_[a];
                tb = (hi - origin[a]) / dir_[a];
            } else {
                invDir_[a] = 1.0 / dir_[a];
                ta = (lo - origin[a]) * invDir_[a];
                tb = (hi - origin[a]) * invDir_[a];
            }
            if (ta > tb) std::swap(ta, tb);
            t0 = std::max(t0, ta);
            t1 = std::min(t1, tb);
        }
        if (!(t0 <= t1)) return;  // misses the grid (or overflowed to +-inf: far beyond it)
        for (int a = 0; a < 3; ++a) p0_[a] = dir_[a] == 0 ? origin[a] : origin[a] + t0 * dir_[a];
        tEnd_ = t1 - t0;
    } else {
        // Zero direction: the segment is the single point origin.
        for (int a = 0; a < 3; ++a) p0_[a] = origin[a];
        tEnd_ = 0;
    }

    for (int a = 0; a < 3; ++a) {
        // When the clip entered through a grid face, p0 lies on the margin-enlarged face,
        // and rounding may put it a hair outside; twice the margin keeps the first cell.
        // (An extra cell in the range is harmless: its leave time is <= 0 and is processed
        // before anything else.) Failing even then means the segment never got near.
        if (!grid.CellRange(a, p0_[a], p0_[a], 2 * margin_[a], first_[a], last_[a])) return;
    }
    for (int a = 0; a < 3; ++a) {
        const double lo = grid.Boundary(a, 0);
        if (slow[a]) {
            // no events: see above
        } else if (dir_[a] > 0) {
            // Cell last+1 is entered at boundary last+1 - margin; cell first is left at
            // boundary first+1 + margin; there is no cell to enter past boundary n-1.
            step_[a] = 1;
            enterBase_[a] = lo - margin_[a] - p0_[a];
            leaveBase_[a] = lo + margin_[a] - p0_[a];
            enterK_[a] = last_[a] + 1;
            leaveK_[a] = first_[a] + 1;
            enterStop_[a] = res_[a];
        } else if (dir_[a] < 0) {
            // Mirror image: cell first-1 is entered at boundary first + margin, cell last
            // is left at boundary last - margin, and boundary 0 has nothing below it.
            step_[a] = -1;
            enterBase_[a] = lo + margin_[a] - p0_[a];
            leaveBase_[a] = lo - margin_[a] - p0_[a];
            enterK_[a] = first_[a];
            leaveK_[a] = last_[a];
            enterStop_[a] = 0;
        }
        if (step_[a] != 0) {
            enterT_[a] = enterK_[a] == enterStop_[a] ? kInf : EventT(a, enterBase_[a], enterK_[a]);
            leaveT_[a] = EventT(a, leaveBase_[a], leaveK_[a]);
        }  // else: a static axis keeps its range and has no events (times stay +inf)
        emitFirst_[a] = cur_[a] = first_[a];
        emitLast_[a] = last_[a];
    }
    emitting_ = true;
    done_ = false;
}

bool SegmentWalker::SlowNext(std::uint32_t &voxel) {
    for (;;) {
        Advance();
        if (emitting_) return Emit(voxel);
        if (done_) return false;
    }
}

void SegmentWalker::Advance() {
    int ea = 0;
    double te = enterT_[0];
    if (enterT_[1] < te) te = enterT_[1], ea = 1;
    if (enterT_[2] < te) te = enterT_[2], ea = 2;
    int la = 0;
    double tl = leaveT_[0];
    if (leaveT_[1] < tl) tl = leaveT_[1], la = 1;
    if (leaveT_[2] < tl) tl = leaveT_[2], la = 2;
    if (tl < te) {
        // Leave: the trailing cell on axis la is no longer touched.
        if (!(tl <= tEnd_) || first_[la] == last_[la]) {
            done_ = true;  // segment ended, or left the grid on this axis
            return;
        }
        if (step_[la] > 0)
            ++first_[la];
        else
            --last_[la];
        leaveK_[la] += step_[la];
        leaveT_[la] = EventT(la, leaveBase_[la], leaveK_[la]);
        return;
    }
    if (!(te <= tEnd_)) {
        done_ = true;
        return;
    }
    // Enter (ties with a leave go here: the closed cells still touch at that t): the next
    // cell on axis ea is touched; yield it times the current ranges of the other axes.
    const int cell = step_[ea] > 0 ? ++last_[ea] : --first_[ea];
    enterK_[ea] += step_[ea];
    enterT_[ea] = enterK_[ea] == enterStop_[ea] ? kInf : EventT(ea, enterBase_[ea], enterK_[ea]);
    for (int a = 0; a < 3; ++a) {
        emitFirst_[a] = first_[a];
        emitLast_[a] = last_[a];
    }
    emitFirst_[ea] = emitLast_[ea] = cell;
    for (int a = 0; a < 3; ++a) cur_[a] = emitFirst_[a];
    emitting_ = true;
}

}  // namespace povrayfc
