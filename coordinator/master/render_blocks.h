// render_blocks.h - the render block size of the slaves' renderers.
//
// POV-Ray traces a frame in square render blocks (Render_Block_Size, default 32) on a grid
// from the render area's corner, and a job traces every block its tiles meet (frame control).
// A tile edge that cuts a block makes the slaves on both sides trace all of it: with the
// paper's 80-pixel tiles that is a fifth more rays. Under antialiasing method 1 a pixel
// depends on the block grid (each block traces a border around itself), so the grid must stay
// the one a single process uses. Under every other setting no pixel depends on it (patch 0201
// makes the shadow cache exact; see ../shared/notes/povray-internals.md, "Determinism"), and
// a block size that divides the tile edge puts every block inside one tile.
#pragma once

#include "povray_probe.h"

namespace fc {

// Whether the resolved options (probe_resolved_options) antialias with method 1, the only
// setting under which a pixel depends on the block grid.
bool pixels_depend_on_block_grid(const ResolvedOptions &ini);

// Blocks from 8 to 64 pixels a side. Every block costs the renderer a message and a set-up
// (Newton at 320x240: one process took 40% more CPU with 8-pixel blocks than with 32; the
// renderers of frame division with 80-pixel tiles 6% more with 20-pixel blocks than with 40),
// so larger is cheaper, while a slave's threads still share a job's blocks.
const int kSmallestBlock = 8, kLargestBlock = 64;

// The block size the slaves should render tiles of `tile` pixels with, or 0 to keep the
// user's options: 0 when pixels depend on the grid or the block size in force already divides
// the tile; else the largest divisor of the tile from kSmallestBlock to kLargestBlock (40 for
// the paper's 80), else 0.
int slave_render_block(const ResolvedOptions &ini, int tile);

} // namespace fc
