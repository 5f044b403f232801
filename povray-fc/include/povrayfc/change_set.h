// ChangeSet: what changed between two frames, and its translation into dirty voxels.
#ifndef POVRAYFC_CHANGE_SET_H
#define POVRAYFC_CHANGE_SET_H

#include <string>
#include <vector>

#include "povrayfc/geometry.h"
#include "povrayfc/voxel_grid.h"
#include "povrayfc/voxel_set.h"

namespace povrayfc {

// Changes are boxes of space whose contents differ between the frames (for a moved object:
// its old and its new bounding box), or "everything" for changes that are not local in
// space (camera, lights, global settings, atmosphere...). Built single-threaded, typically
// while comparing the parsed scenes of two frames.
class ChangeSet {
  public:
    // Something inside b changed. An empty box (lo > hi) encloses nothing and is ignored;
    // an infinite box is fine (it makes everything dirty). Throws std::invalid_argument
    // for a box with NaN: a NaN bound is a bug upstream, and guessing would hide it.
    void AddBox(const Box &b);
    // Something inside both b and the capsule changed (the capsule is a tighter hull).
    void AddBox(const Box &b, const Capsule &hull);
    // Everything changed. The first reason is kept for logs and the next frame's report.
    // Throws std::invalid_argument for a null reason.
    void MarkAll(const char *reason);
    void Clear();

    bool AllMarked() const { return all_; }
    const std::string &Reason() const { return reason_; }
    const std::vector<Box> &Boxes() const { return boxes_; }
    // Per box: its capsule hull, if it has one.
    const std::vector<Capsule> &Hulls() const { return hulls_; }
    const std::vector<bool> &HasHull() const { return hasHull_; }
    // No change at all: the previous frame can be reused as it is.
    bool Empty() const { return !all_ && boxes_.empty(); }

  private:
    std::vector<Box> boxes_;
    std::vector<Capsule> hulls_;
    std::vector<bool> hasHull_;
    bool all_ = false;
    std::string reason_;
};

struct DirtyResult {
    VoxelSet voxels;  // every voxel whose closed cell meets a changed box (all if `all`)
    bool all = false;  // everything must be re-traced, including pixels whose rays met no voxel
    std::string reason;  // why `all` is set
};

// Marks every voxel overlapped by a changed box. If the change set is marked "all", or a
// changed box is not inside the grid (it left the grid or is unbounded, so rays that were
// never recorded may see it), the result is `all` with a reason, and every voxel is set.
DirtyResult DirtyVoxels(const VoxelGrid &grid, const ChangeSet &changes);

}  // namespace povrayfc

#endif
