// DependencyStore: per-pixel lists of the voxels a pixel's rays touched, compactly encoded.
//
// Layout (chosen by measurement, see povrayfc_bench and README.md): one pointer per pixel
// to its own heap block holding the pixel's voxel ids sorted ascending, as gaps between
// consecutive ids in 1 or 2 bytes with a 1-bit-per-entry length stream (see voxel_list.h).
// Measured with povrayfc_bench (64^3 grid, 1920x1080, synthetic camera/shadow/mirror rays):
//   ~80 entries/pixel:  1.67 B/entry (headers included), 141 B/pixel, 293 MB (309 MB heap)
//   ~150 entries/pixel: 1.50 B/entry, 235 B/pixel, 488 MB (520 MB heap): far under 4 GiB.
// DirtyPixels over 1920x1080 decodes every entry of every clean pixel: ~1.2-2 ns/entry,
// 0.2-0.37 s for ~150 entries/pixel; ~2 ms when nothing changed (no decoding).
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

    // Replaces pixel (x, y)'s list with the recorder's voxels (or the "everything" mark).
    // Sorts the recorder's list in place but leaves it otherwise intact. Thread-safe for
    // distinct pixels. Throws std::invalid_argument for (x, y) outside the image.
    void Commit(int x, int y, PixelRecorder &recorder);
    // Forgets pixel (x, y): it counts as dirty until committed again.
    void Clear(int x, int y);
    void ClearAll();

    // The pixel has a recorded list (possibly empty: its rays met no voxel).
    bool Has(int x, int y) const { return slots_[Slot(x, y)] != nullptr; }
    // The pixel was committed with PixelRecorder::MarkEverything().
    bool DependsOnEverything(int x, int y) const { return slots_[Slot(x, y)] == EverythingBlock(); }

    // Calls f(uint32_t voxel) for each voxel of pixel (x, y), ascending. Nothing for a
    // pixel without a list or with the "everything" mark.
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
