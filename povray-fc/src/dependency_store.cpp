// DependencyStore: encoding committed pixels, freeing replaced blocks, computing dirty pixels.
#include "povrayfc/dependency_store.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>

namespace povrayfc {

namespace {
// Both markers encode "0 payload bytes"; only their addresses differ.
const std::uint8_t kEmptyBlock[1] = {0};
const std::uint8_t kEverythingBlock[1] = {0};
}  // namespace

const std::uint8_t *DependencyStore::EmptyBlock() { return kEmptyBlock; }
const std::uint8_t *DependencyStore::EverythingBlock() { return kEverythingBlock; }

DependencyStore::DependencyStore(int width, int height) : width_(width), height_(height) {
    if (width <= 0 || height <= 0)
        throw std::invalid_argument("DependencyStore: image size must be positive, got " + std::to_string(width) +
                                    "x" + std::to_string(height));
    std::size_t pixels = std::size_t(width) * std::size_t(height);
    if (pixels > (std::size_t(1) << 31))
        throw std::invalid_argument("DependencyStore: image of " + std::to_string(width) + "x" +
                                    std::to_string(height) + " pixels is too large");
    slots_.assign(pixels, nullptr);
}

DependencyStore::~DependencyStore() { FreeAll(); }

DependencyStore::DependencyStore(DependencyStore &&other) noexcept
    : width_(other.width_), height_(other.height_), slots_(std::move(other.slots_)) {
    other.slots_.clear();
    other.width_ = other.height_ = 0;
}

DependencyStore &DependencyStore::operator=(DependencyStore &&other) noexcept {
    if (this != &other) {
        FreeAll();
        width_ = other.width_;
        height_ = other.height_;
        slots_ = std::move(other.slots_);
        other.slots_.clear();
        other.width_ = other.height_ = 0;
    }
    return *this;
}

void DependencyStore::ThrowOutside(int x, int y) const {
    throw std::invalid_argument("DependencyStore: pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                                ") is outside the " + std::to_string(width_) + "x" + std::to_string(height_) +
                                " image");
}

void DependencyStore::Free(const std::uint8_t *block) {
    if (block && block != kEmptyBlock && block != kEverythingBlock) delete[] block;
}

void DependencyStore::FreeAll() {
    for (const std::uint8_t *&b : slots_) {
        Free(b);
        b = nullptr;
    }
}

void DependencyStore::Commit(int x, int y, PixelRecorder &recorder) {
    std::size_t slot = Slot(x, y);
    const std::uint8_t *block;
    if (recorder.Everything()) {
        block = kEverythingBlock;
    } else if (recorder.Voxels().empty()) {
        block = kEmptyBlock;
    } else {
        // Insertion order, no sort: the recorder's list is already unique (see voxel_list.h).
        const std::vector<std::uint32_t> &ids = recorder.Voxels();
        block = NewVoxelList(ids.data(), ids.size());
    }
    // Only this thread touches this slot (distinct pixels per thread), so no lock.
    const std::uint8_t *old = slots_[slot];
    slots_[slot] = block;
    Free(old);
}

void DependencyStore::Clear(int x, int y) {
    std::size_t slot = Slot(x, y);
    Free(slots_[slot]);
    slots_[slot] = nullptr;
}

void DependencyStore::ClearAll() { FreeAll(); }

std::size_t DependencyStore::VoxelCountAt(int x, int y) const {
    const std::uint8_t *p = slots_[Slot(x, y)];
    return (p && p != kEmptyBlock && p != kEverythingBlock) ? VoxelListCount(p) : 0;
}

void DependencyStore::DirtyRows(const VoxelSet &dirty, int y0, int y1, DirtyMask &mask) const {
    const bool any = dirty.Any();
    const std::uint64_t *words = dirty.Words();
    // Ids the set does not cover (>= Size()) count as dirty: they are unknown, and this
    // keeps the bit lookup in bounds.
    const std::uint32_t size = std::uint32_t(std::min<std::size_t>(dirty.Size(), 0xffffffffu));
    for (int y = y0; y < y1; ++y) {
        const std::uint8_t *const *row = slots_.data() + std::size_t(y) * std::size_t(width_);
        for (int x = 0; x < width_; ++x) {
            const std::uint8_t *p = row[x];
            if (!p) {
                mask.Set(x, y);  // no record: must be traced
                continue;
            }
            if (!any || p == kEmptyBlock) continue;  // nothing changed / depends on nothing
            if (p == kEverythingBlock ||
                DecodeVoxelList(p, [&](std::uint32_t v) { return v >= size || (words[v >> 6] >> (v & 63) & 1); }))
                mask.Set(x, y);
        }
    }
}

DirtyMask DependencyStore::DirtyPixels(const VoxelSet &dirty, int threads) const {
    DirtyMask mask(width_, height_);
    if (threads <= 0) threads = int(std::max(1u, std::thread::hardware_concurrency()));
    threads = std::min(threads, height_);
    if (threads == 1) {
        DirtyRows(dirty, 0, height_, mask);
        return mask;
    }
    // Contiguous row bands: each thread writes only its own rows of the mask (one byte per
    // pixel, so no shared words).
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t) {
        int y0 = int(std::int64_t(height_) * t / threads), y1 = int(std::int64_t(height_) * (t + 1) / threads);
        pool.emplace_back([this, &dirty, &mask, y0, y1] { DirtyRows(dirty, y0, y1, mask); });
    }
    for (std::thread &t : pool) t.join();
    return mask;
}

DirtyMask DependencyStore::DirtyPixels(const DirtyResult &changes, int threads) const {
    if (changes.all) {
        DirtyMask mask(width_, height_);
        mask.SetAll();
        return mask;
    }
    return DirtyPixels(changes.voxels, threads);
}

std::size_t DependencyStore::MemoryBytes() const {
    std::size_t bytes = sizeof(*this) + slots_.capacity() * sizeof(slots_[0]);
    for (const std::uint8_t *b : slots_) {
        if (!b || b == kEmptyBlock || b == kEverythingBlock) continue;
        bytes += VoxelListBlockSize(b);
    }
    return bytes;
}

std::size_t DependencyStore::BlockCount() const {
    std::size_t n = 0;
    for (const std::uint8_t *b : slots_) n += b && b != kEmptyBlock && b != kEverythingBlock;
    return n;
}

std::size_t DependencyStore::EntryCount() const {
    std::size_t n = 0;
    for (int y = 0; y < height_; ++y)
        for (int x = 0; x < width_; ++x) n += VoxelCountAt(x, y);
    return n;
}

}  // namespace povrayfc
