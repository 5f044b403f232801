// DirtyMask: which pixels of a W x H image must be re-traced in the next frame.
#ifndef POVRAYFC_DIRTY_MASK_H
#define POVRAYFC_DIRTY_MASK_H

#include <cassert>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace povrayfc {

// One byte per pixel rather than one bit: render threads may read it concurrently and a
// builder may write distinct pixels concurrently without sharing a word (2 MB at 1080p).
class DirtyMask {
  public:
    DirtyMask() = default;
    // All clear. Throws std::invalid_argument for non-positive sizes.
    DirtyMask(int width, int height);

    int Width() const { return width_; }
    int Height() const { return height_; }
    bool Test(int x, int y) const {
        assert(x >= 0 && x < width_ && y >= 0 && y < height_);
        return pixels_[std::size_t(y) * width_ + x] != 0;
    }
    void Set(int x, int y, bool dirty = true) {
        assert(x >= 0 && x < width_ && y >= 0 && y < height_);
        pixels_[std::size_t(y) * width_ + x] = dirty;
    }
    void SetAll();
    // Number of dirty pixels.
    std::size_t Count() const;

  private:
    int width_ = 0, height_ = 0;
    std::vector<std::uint8_t> pixels_;
};

}  // namespace povrayfc

#endif
