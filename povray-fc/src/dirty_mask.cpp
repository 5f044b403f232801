// DirtyMask: construction with size checks, fill and count.
#include "povrayfc/dirty_mask.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace povrayfc {

DirtyMask::DirtyMask(int width, int height) : width_(width), height_(height) {
    if (width <= 0 || height <= 0)
        throw std::invalid_argument("DirtyMask: size must be positive, got " + std::to_string(width) + "x" +
                                    std::to_string(height));
    pixels_.assign(std::size_t(width) * std::size_t(height), 0);
}

void DirtyMask::SetAll() { std::fill(pixels_.begin(), pixels_.end(), 1); }

std::size_t DirtyMask::Count() const { return std::size_t(std::count(pixels_.begin(), pixels_.end(), 1)); }

}  // namespace povrayfc
