// ChangeSet bookkeeping and DirtyVoxels: changed boxes to dirty voxels, or "everything".
#include "povrayfc/change_set.h"

#include <stdexcept>

namespace povrayfc {

void ChangeSet::AddBox(const Box &b) {
    if (b.HasNaN()) throw std::invalid_argument("ChangeSet::AddBox: box contains NaN: " + ToString(b));
    if (b.Empty()) return;
    boxes_.push_back(b);
}

void ChangeSet::MarkAll(const char *reason) {
    if (!reason) throw std::invalid_argument("ChangeSet::MarkAll: reason must not be null");
    if (!all_) reason_ = reason;
    all_ = true;
}

void ChangeSet::Clear() {
    boxes_.clear();
    all_ = false;
    reason_.clear();
}

DirtyResult DirtyVoxels(const VoxelGrid &grid, const ChangeSet &changes) {
    DirtyResult r;
    r.voxels = VoxelSet(grid.VoxelCount());
    if (changes.AllMarked()) {
        r.all = true;
        r.reason = changes.Reason();
    } else {
        for (const Box &b : changes.Boxes()) {
            if (!grid.BoxInside(b)) {
                // Rays are recorded only inside the grid, so a change outside it may affect
                // pixels whose rays we never saw there.
                r.all = true;
                r.reason = std::string(b.IsFinite() ? "changed box " : "unbounded changed box ") + ToString(b) +
                           " is not inside the voxel grid " + ToString(grid.Bounds());
                break;
            }
            grid.ForEachVoxelOverlapping(b, [&](std::uint32_t v) { r.voxels.Set(v); });
        }
    }
    if (r.all) r.voxels.SetAll();
    return r;
}

}  // namespace povrayfc
