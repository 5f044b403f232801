// DependencyStore: per-pixel lists of the voxels a pixel's rays touched, compactly encoded.
//
// Layout (chosen by measurement, see povrayfc_bench and README.md): one pointer per pixel
// to its own heap block holding the pixel's voxel ids in the order the PixelRecorder first
// saw them (unique, NOT sorted), as signed steps between consecutive ids in 1 or 2 bytes
// with a 1-bit-per-entry length stream (see voxel_list.h). Rays walk the grid voxel by
// voxel, so consecutive ids mostly differ by +-1, +-nx or +-nx*ny and the steps are as
// small as the ascending gaps of a sorted list were; not sorting made Commit 5-8x cheaper
// (the sort was ~18% of a real render with fc on, the whole commit ~28%).
// Measured with povrayfc_bench (64^3 grid, 1920x1080, synthetic camera/shadow/mirror rays,
// loaded 2-vCPU VM; before -> after dropping the sort):
//   ~80 entries/pixel:  Commit 1030 -> 185 ns/pixel; 1.674 -> 1.694 B/entry (headers
//                       included), 143 B/pixel, 296 MB (312 MB heap)
//   ~150 entries/pixel: Commit 2480 -> 290 ns/pixel; 1.502 -> 1.558 B/entry, 244 B/pixel,
//                       505 MB (538 MB heap): far under 4 GiB.
// DirtyPixels over 1920x1080 decodes every entry of every clean pixel: ~0.9-1 ns/entry,
// 130-155 ms at ~80 entries/pixel and 220-305 ms at ~150 (1 thread, CPU time; 185-205 /
// 295-360 ms before); ~2 ms when nothing changed (no decoding).
//
// Why a block per pixel rather than shared arenas: Commit() from several render threads
// then needs no lock at all (each thread writes only its own pixels' slots; malloc is
// thread-safe), a re-traced pixel frees its old block instead of leaving garbage that
// needs compaction, and the whole overhead is the 8-byte slot plus malloc's header,
// small next to the ~100-200 byte payload. Pixels whose rays missed the grid share a
// static empty block, and "depends on everything" pixels a static marker block, so the
// common background pixel allocates nothing.
//
// Threading contract: Commit() and Clear() may run concurrently from several threads for
// DIFFERENT pixels. Reads (Has, ForEachVoxel, DirtyPixels, MemoryBytes...) must not overlap
// with writes; in povray-fc they happen between frames.
#ifndef POVRAYFC_DEPENDENCY_STORE_H
#define POVRAYFC_DEPENDENCY_STORE_H

#include <cstddef>
#include <cstdint>
#include <vector>

#include "povrayfc/change_set.h"
#include "povrayfc/dirty_mask.h"
#include "povrayfc/pixel_recorder.h"
#include "povrayfc/voxel_list.h"
#include "povrayfc/voxel_set.h"

namespace povrayfc {

class DependencyStore {
  public:
    // Sized to the full image (the rendered region may be any sub-rectangle of it).
    // Throws std::invalid_argument for non-positive or absurd (> 2^31 pixels) sizes.
    DependencyStore(int width, int height);
    ~DependencyStore();
    DependencyStore(const DependencyStore &) = delete;
    DependencyStore &operator=(const DependencyStore &) = delete;
    DependencyStore(DependencyStore &&other) noexcept;
    DependencyStore &operator=(DependencyStore &&other) noexcept;

    int Width() const { return width_; }
    int Height() const { return height_; }

    // Replaces pixel (x, y)'s list with the recorder's voxels (or the "everything" mark),
    // encoded in the recorder's order in one pass (no sort); the recorder is left as it was.
    // Thread-safe for distinct pixels. Throws std::invalid_argument for (x, y) outside the
    // image.
    void Commit(int x, int y, PixelRecorder &recorder);
    // Forgets pixel (x, y): it counts as dirty until committed again.
    void Clear(int x, int y);
    void ClearAll();

    // The pixel has a recorded list (possibly empty: its rays met no voxel).
    bool Has(int x, int y) const { return slots_[Slot(x, y)] != nullptr; }
    // The pixel was committed with PixelRecorder::MarkEverything().
    bool DependsOnEverything(int x, int y) const { return slots_[Slot(x, y)] == EverythingBlock(); }

    // Calls f(uint32_t voxel) once for each voxel of pixel (x, y), in NO particular order
    // (today: the order the recorder first saw them; not ascending since Commit stopped
    // sorting). Nothing for a pixel without a list or with the "everything" mark.
    template <class F>
    void ForEachVoxel(int x, int y, F f) const {
        const std::uint8_t *p = slots_[Slot(x, y)];
        if (!p || p == EmptyBlock() || p == EverythingBlock()) return;
        DecodeVoxelList(p, [&](std::uint32_t v) {
            f(v);
            return false;
        });
    }
    std::size_t VoxelCountAt(int x, int y) const;

    // Pixels that must be re-traced: those with no list (never rendered, or cleared), those
    // depending on a voxel in `dirty` or on a voxel id >= dirty.Size() (recorded against
    // another grid: unknown, so dirty), and "everything" pixels when any voxel is dirty.
    // threads > 1 splits the rows over that many std::threads (<= 0: one per hardware
    // thread); the default, 1, runs on the calling thread.
    DirtyMask DirtyPixels(const VoxelSet &dirty, int threads = 1) const;
    // As above, but every pixel is dirty when changes.all is set (pixels whose rays met no
    // voxel included: a camera or light change affects them too).
    DirtyMask DirtyPixels(const DirtyResult &changes, int threads = 1) const;

    // Bytes this store allocated: the slot array plus every pixel's block (allocator
    // bookkeeping, ~8-16 bytes per block with glibc, not included).
    std::size_t MemoryBytes() const;
    // Number of heap blocks (pixels with a non-empty list): MemoryBytes() plus about 16 B
    // times this is the real heap use.
    std::size_t BlockCount() const;
    // Total voxel entries over all pixels.
    std::size_t EntryCount() const;

  private:
    static const std::uint8_t *EmptyBlock();
    static const std::uint8_t *EverythingBlock();

    std::size_t Slot(int x, int y) const {
        if (x < 0 || x >= width_ || y < 0 || y >= height_) ThrowOutside(x, y);
        return std::size_t(y) * std::size_t(width_) + std::size_t(x);
    }
    [[noreturn]] void ThrowOutside(int x, int y) const;
    static void Free(const std::uint8_t *block);
    void DirtyRows(const VoxelSet &dirty, int y0, int y1, DirtyMask &mask) const;
    void FreeAll();

    int width_ = 0, height_ = 0;
    std::vector<const std::uint8_t *> slots_;  // nullptr: no list
};

}  // namespace povrayfc

#endif
