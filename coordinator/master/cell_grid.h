// cell_grid.h - which tiles of which frames are done: a frame's cells.
//
// A cell is one tile of one frame, addressed by frame index (0..frames-1) and tile number. It
// is done once its pixels reached the master, or when its frame needs no more work (already
// on disk, skipped by a Pre_Frame_Command, given up). The frame book (frame_book.h) keeps the
// one grid of a run and marks it; the schedule (schedule.h) reads it to know what is missing.
#pragma once

#include <cstddef>
#include <vector>

namespace fc {

class CellGrid {
public:
    CellGrid(int frames, int tiles);

    int frames() const { return frames_; }
    int tiles() const { return tiles_; }

    bool done(int index, int tile) const { return done_[cell(index, tile)] != 0; }
    bool frame_done(int index) const { return frame_cells_[size_t(index)] == tiles_; }
    int frames_done() const { return frames_done_; }
    long cells_done() const { return cells_done_; }
    bool all_done() const { return frames_done_ == frames_; }

    // Mark one cell done; false when it was done already.
    bool mark(int index, int tile);
    // Mark every cell of a frame done.
    void mark_frame(int index);

private:
    size_t cell(int index, int tile) const { return size_t(index) * size_t(tiles_) + size_t(tile); }

    int frames_, tiles_;
    std::vector<char> done_;            // frame-major
    std::vector<int> frame_cells_;      // done cells per frame
    int frames_done_ = 0;
    long cells_done_ = 0;
};

} // namespace fc
