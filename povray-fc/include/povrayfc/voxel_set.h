// VoxelSet: a bitset over the voxels of one grid (the dirty voxels of a frame).
#ifndef POVRAYFC_VOXEL_SET_H
#define POVRAYFC_VOXEL_SET_H

#include <cstddef>
#include <cstdint>
#include <vector>

namespace povrayfc {

// One bit per voxel: 32 KiB for a 64^3 grid, so DirtyPixels' lookups stay in L1/L2.
class VoxelSet {
  public:
    VoxelSet() = default;
    // An empty set over voxel ids [0, size).
    explicit VoxelSet(std::size_t size);

    std::size_t Size() const { return size_; }
    // Throws std::invalid_argument for voxel >= Size().
    void Set(std::uint32_t voxel);
    // False for voxel >= Size() (an id the set does not cover is not in it).
    bool Test(std::uint32_t voxel) const {
        return voxel < size_ && (words_[voxel >> 6] >> (voxel & 63) & 1) != 0;
    }
    void SetAll();
    void Reset();
    // Number of voxels in the set.
    std::size_t Count() const;
    bool Any() const;
    // Raw 64-bit words (bit v%64 of word v/64 is voxel v), for tight loops.
    const std::uint64_t *Words() const { return words_.data(); }

  private:
    std::size_t size_ = 0;
    std::vector<std::uint64_t> words_;
};

}  // namespace povrayfc

#endif
