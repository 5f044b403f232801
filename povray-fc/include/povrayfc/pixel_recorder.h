// PixelRecorder: per-thread collector of the unique voxels the rays of one pixel touched.
#ifndef POVRAYFC_PIXEL_RECORDER_H
#define POVRAYFC_PIXEL_RECORDER_H

#include <cassert>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace povrayfc {

// One recorder per render thread, reused for every pixel: Begin(), Add() for each voxel of
// each ray (e.g. from WalkSegment), then DependencyStore::Commit(). After warm-up nothing
// allocates.
//
// Dedupe: a walker never repeats a voxel within one ray, but the camera, shadow, reflected
// and (with anti-aliasing) sub-sample rays of a pixel overlap heavily, so Add() first
// drops an immediate repeat and then checks a small open-addressing hash set whose slots
// carry an epoch stamp, which makes Begin() O(1). Only unique ids are kept, in first-seen
// order, which is the order the rays walked them; DependencyStore::Commit encodes them in
// that order (consecutive ids are mostly grid neighbours) and does not sort them.
class PixelRecorder {
  public:
    PixelRecorder();

    // Starts a new pixel: forgets all voxels and the "everything" mark.
    void Begin() {
        list_.clear();
        last_ = kNone;
        everything_ = false;
        if (++epoch_ == 0) ResetStamps();  // every 2^32 pixels
    }

    // Records that the pixel depends on voxel (an id < VoxelGrid::kMaxVoxels).
    void Add(std::uint32_t voxel) {
        assert(voxel != kNone);
        if (voxel == last_) return;
        last_ = voxel;
        std::uint32_t i = Hash(voxel);
        for (;;) {
            if (stamps_[i] != epoch_) break;
            if (keys_[i] == voxel) return;
            i = (i + 1) & mask_;
        }
        stamps_[i] = epoch_;
        keys_[i] = voxel;
        list_.push_back(voxel);
        if (list_.size() * 2 > keys_.size()) Grow();
    }

    // The pixel depends on something the voxels cannot express (a ray the walker rejected,
    // an effect not traced as segments): any change at all must re-trace it.
    void MarkEverything() { everything_ = true; }
    bool Everything() const { return everything_; }

    // Unique voxels recorded so far, in first-seen order (until SortedVoxels() is called).
    const std::vector<std::uint32_t> &Voxels() const { return list_; }
    // Sorts the recorded voxels in place and returns them. For tests and tools: the commit
    // path does not sort.
    const std::vector<std::uint32_t> &SortedVoxels();

  private:
    static constexpr std::uint32_t kNone = 0xffffffffu;

    std::uint32_t Hash(std::uint32_t v) const { return (v * 0x9E3779B1u) >> shift_ & mask_; }
    void Grow();
    void ResetStamps();

    std::vector<std::uint32_t> list_;
    std::vector<std::uint32_t> keys_, stamps_;
    std::uint32_t mask_ = 0, epoch_ = 1, last_ = kNone;
    int shift_ = 0;
    bool everything_ = false;
};

}  // namespace povrayfc

#endif
