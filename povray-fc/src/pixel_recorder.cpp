// PixelRecorder: hash-set growth and stamp reset (the rare paths of Add and Begin).
#include "povrayfc/pixel_recorder.h"

#include <algorithm>

namespace povrayfc {

namespace {
constexpr int kInitialLog2 = 9;  // 512 slots: room for ~256 unique voxels before growing
}

PixelRecorder::PixelRecorder()
    : keys_(std::size_t(1) << kInitialLog2, 0), stamps_(std::size_t(1) << kInitialLog2, 0) {
    mask_ = (1u << kInitialLog2) - 1;
    shift_ = 32 - kInitialLog2;
    list_.reserve(std::size_t(1) << (kInitialLog2 - 1));
}

void PixelRecorder::Grow() {
    std::size_t size = keys_.size() * 2;
    keys_.assign(size, 0);
    stamps_.assign(size, 0);
    mask_ = std::uint32_t(size - 1);
    --shift_;
    // Slots were wiped, so stamp 0 never matches epoch_ (which is never 0).
    for (std::uint32_t v : list_) {
        std::uint32_t i = Hash(v);
        while (stamps_[i] == epoch_) i = (i + 1) & mask_;
        stamps_[i] = epoch_;
        keys_[i] = v;
    }
}

void PixelRecorder::ResetStamps() {
    std::fill(stamps_.begin(), stamps_.end(), 0);
    epoch_ = 1;
}

const std::vector<std::uint32_t> &PixelRecorder::SortedVoxels() {
    std::sort(list_.begin(), list_.end());
    return list_;
}

}  // namespace povrayfc
