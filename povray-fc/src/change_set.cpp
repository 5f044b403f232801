// ChangeSet bookkeeping and DirtyVoxels: changed boxes to dirty voxels, or "everything".
#include "povrayfc/change_set.h"

#include <cmath>
#include <stdexcept>

namespace povrayfc {

void ChangeSet::AddBox(const Box &b) {
    if (b.HasNaN()) throw std::invalid_argument("ChangeSet::AddBox: box contains NaN: " + ToString(b));
    if (b.Empty()) return;
    boxes_.push_back(b);
    hulls_.emplace_back();
    hasHull_.push_back(false);
}

void ChangeSet::AddBox(const Box &b, const Capsule &hull) {
    if (hull.a.HasNaN() || hull.b.HasNaN() || std::isnan(hull.radius))
        throw std::invalid_argument("ChangeSet::AddBox: capsule contains NaN");
    const std::size_t before = boxes_.size();
    AddBox(b);
    if (boxes_.size() == before) return;
    hulls_.back() = hull;
    hasHull_.back() = true;
}

void ChangeSet::MarkAll(const char *reason) {
    if (!reason) throw std::invalid_argument("ChangeSet::MarkAll: reason must not be null");
    if (!all_) reason_ = reason;
    all_ = true;
}

void ChangeSet::Clear() {
    boxes_.clear();
    hulls_.clear();
    hasHull_.clear();
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
        for (std::size_t i = 0; i < changes.Boxes().size(); ++i) {
            const Box &b = changes.Boxes()[i];
            if (!grid.BoxInside(b)) {
                // Rays are recorded only inside the grid, so a change outside it may affect
                // pixels whose rays we never saw there.
                r.all = true;
                r.reason = std::string(b.IsFinite() ? "changed box " : "unbounded changed box ") + ToString(b) +
                           " is not inside the voxel grid " + ToString(grid.Bounds());
                break;
            }
            if (!changes.HasHull()[i]) {
                grid.ForEachVoxelOverlapping(b, [&](std::uint32_t v) { r.voxels.Set(v); });
                continue;
            }
            const Capsule &hull = changes.Hulls()[i];
            grid.ForEachVoxelOverlapping(b, [&](std::uint32_t v) {
                int ix, iy, iz;
                grid.Coords(v, ix, iy, iz);
                if (hull.MayMeet(grid.VoxelBox(ix, iy, iz))) r.voxels.Set(v);
            });
        }
    }
    if (r.all) r.voxels.SetAll();
    return r;
}

}  // namespace povrayfc
