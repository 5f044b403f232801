// VoxelSet: sizing, setting with a range check, and counting.
#include "povrayfc/voxel_set.h"

#include <algorithm>
#include <bitset>
#include <stdexcept>
#include <string>

namespace povrayfc {

VoxelSet::VoxelSet(std::size_t size) : size_(size), words_((size + 63) / 64, 0) {}

void VoxelSet::Set(std::uint32_t voxel) {
    if (voxel >= size_)
        throw std::invalid_argument("VoxelSet::Set: voxel " + std::to_string(voxel) +
                                    " out of range (set size " + std::to_string(size_) + ")");
    words_[voxel >> 6] |= std::uint64_t(1) << (voxel & 63);
}

void VoxelSet::SetAll() {
    std::fill(words_.begin(), words_.end(), ~std::uint64_t(0));
    // Keep bits past size_ clear so Count() and Words() users see only real voxels.
    if (size_ % 64) words_.back() = (std::uint64_t(1) << (size_ % 64)) - 1;
}

void VoxelSet::Reset() { std::fill(words_.begin(), words_.end(), 0); }

std::size_t VoxelSet::Count() const {
    std::size_t n = 0;
    for (std::uint64_t w : words_) n += std::bitset<64>(w).count();
    return n;
}

bool VoxelSet::Any() const {
    return std::any_of(words_.begin(), words_.end(), [](std::uint64_t w) { return w != 0; });
}

}  // namespace povrayfc
