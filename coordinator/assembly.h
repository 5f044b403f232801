// assembly.h - assembling returned tiles into frames and writing them with OpenImageIO.
//
// A frame lives in memory (8-bit RGB, zeros outside the render area like POV-Ray's own
// partial renders) from its first tile to its last; then it is written as a 24-bit Targa under
// a temporary name in the output directory, fsynced and renamed to POV-Ray's name for it, and
// its memory is freed. So a file under a final name is always complete (resume relies on it),
// and the master holds only the frames in flight. Frames whose pixels were dithered by
// diffusion come as unquantized values and are quantized here, once, over the whole frame.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "dither.h"
#include "protocol.h"

namespace fc {

class FrameAssembly {
public:
    FrameAssembly(const std::string &dir, const std::string &stem, int digits, int width,
                  int height, const std::vector<int> &frames);

    // Final path of frame index i, and its temporary path.
    std::string final_path(int index) const;
    std::string temp_path(int index) const;

    // True if frame index i already exists as a complete image of the right size.
    bool exists_complete(int index) const;

    // Remove temporary files a killed master left behind for our frames.
    void remove_stale_temps() const;

    // Copy the rectangles of one result (encoding "rgb8" or "rgbf", see frame_record.h) into
    // frame index i (allocated on first use). Only rectangles whose `keep` flag is set are
    // copied (the others arrived before). Returns false with err on a malformed payload.
    bool put(int index, const std::vector<Rect> &rects, const std::vector<char> &keep,
             const std::string &encoding, const std::vector<uint8_t> &data, std::string &err);

    // Write frame index i (temp name, fsync, rename) and free its memory.
    bool write(int index, std::string &err);

    // Frames currently held in memory.
    size_t pending() const { return frames_in_flight_.size(); }

private:
    struct Pending {
        std::vector<uint8_t> rgb;               // width * height * 3
        std::vector<float> values;              // diffusion dithering: unquantized, or empty
        std::unique_ptr<Quantizer> quantizer;
    };

    std::string dir_, stem_;
    int digits_, width_, height_;
    std::vector<int> frames_;
    std::map<int, Pending> frames_in_flight_;
};

} // namespace fc
