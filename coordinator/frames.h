// frames.h - assembling returned tiles into frames and writing them with OpenImageIO.
//
// A frame lives in memory (8-bit RGB, zeros outside the render area like POV-Ray's own
// partial renders) until its last tile arrives; then it is written as a 24-bit Targa under a
// temporary name in the output directory and renamed to POV-Ray's name for it. So a file
// under a final name is always complete, which is what resume relies on.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "protocol.h"

namespace fc {

class FrameStore {
public:
    FrameStore(const std::string &dir, const std::string &stem, int digits, int width, int height,
               const std::vector<int> &frames);

    // Final path of frame index i, and its temporary path.
    std::string final_path(int index) const;
    std::string temp_path(int index) const;

    // True if frame index i already exists as a complete image of the right size.
    bool exists_complete(int index) const;

    // Remove temporary files a killed master left behind for our frames.
    void remove_stale_temps() const;

    // Copy one tile of one frame into its buffer (allocated on first use).
    void put(int index, const Rect &rect, const std::vector<uint8_t> &pixels);

    // Write frame index i (temp name, then rename) and free its buffer.
    bool write(int index, std::string &err);

    // Frames currently held in memory.
    size_t pending() const { return buffers_.size(); }

private:
    std::string dir_, stem_;
    int digits_, width_, height_;
    std::vector<int> frames_;
    std::map<int, std::vector<uint8_t>> buffers_;
};

} // namespace fc
