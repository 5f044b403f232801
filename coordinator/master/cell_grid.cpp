// cell_grid.cpp - a frame's cells (see cell_grid.h).
#include "cell_grid.h"

namespace fc {

CellGrid::CellGrid(int frames, int tiles)
    : frames_(frames), tiles_(tiles), done_(size_t(frames) * size_t(tiles), 0),
      frame_cells_(size_t(frames), 0)
{
}

bool CellGrid::mark(int index, int tile)
{
    char &d = done_[cell(index, tile)];
    if (d)
        return false;
    d = 1;
    cells_done_++;
    if (++frame_cells_[size_t(index)] == tiles_)
        frames_done_++;
    return true;
}

void CellGrid::mark_frame(int index)
{
    for (int t = 0; t < tiles_; t++)
        mark(index, t);
}

} // namespace fc
