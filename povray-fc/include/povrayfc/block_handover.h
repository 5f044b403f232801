// BlockHandover: a tile's stored blocks written out by the renderer that leaves the tile
// and read in by the one that takes it over, so the tile's first frame on its new renderer
// re-traces only what changed since, not every pixel (a distributed slave's tiles move to
// balance the hosts' load: coordinator/schedule.h).
//
// A block record is valid for the scene of the frame it was last rendered in (`frame`). The
// renderer that takes it tests its samples against the changes between that frame and the
// one it renders, from the signature of that frame it parsed itself (every renderer parses
// every frame it renders, and both parse the same scene with the same options), so the
// pixels stay those of a full render. The clearances the samples kept (change_drift.h) are
// stamped against the sender's frames: they are dropped, and every sample reached by a
// change is tested in full once. The cones around the segments are rebuilt on first use.
//
// The bytes are the records' own arrays, raw: both ends are the same povray-fc build (the
// header carries the sizes of the stored types, and a mismatch refuses the whole hand-over).
#ifndef POVRAYFC_BLOCK_HANDOVER_H
#define POVRAYFC_BLOCK_HANDOVER_H

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "povrayfc/frame_setup.h"
#include "povrayfc/sample_store.h"

namespace povrayfc {

struct HandedBlock {
    std::uint32_t serial = 0;  // POV-Ray's block number on the render area's block grid
    std::unique_ptr<BlockRecord> record;
};

struct Handover {
    int frame = 0;        // the frame the records were last rendered in
    // The sender's render settings of that frame: the receiver's must be the same.
    int width = 0, height = 0, left = 0, top = 0, right = -1, bottom = -1, blockSize = 0;
    std::uint64_t optionsHash = 0;
    std::vector<HandedBlock> blocks;

    // Whether `setup` (the receiver's setup of the same frame) renders the same grid.
    bool SameGrid(const FrameSetup &setup) const;
};

// The records of `store` meeting one of `rects` (x0, y0, x1, y1, ... half-open, full-image
// pixels), as last rendered in the frame `setup` describes; blocks kept as pixels only
// (opaque) are left out. Appends the bytes to `out`; returns how many blocks went.
std::size_t WriteHandover(const SampleStore &store, const FrameSetup &setup, const std::vector<int> &rects,
                          std::vector<char> &out);

// Reads what WriteHandover wrote. False, with `why` (one line), for bytes that are not a
// hand-over of this build.
bool ReadHandover(const char *data, std::size_t size, Handover &out, std::string &why);

}  // namespace povrayfc

#endif
