// SampleStore: memory and content counts over all blocks.
#include "povrayfc/sample_store.h"

namespace povrayfc {

bool SampleStore::Keep(std::size_t serial) {
    if (serial >= blocks_.size()) return false;
    const std::size_t now = blocks_[serial] ? blocks_[serial]->MemoryBytes() : 0;
    const std::size_t before = bytes_[serial];
    if (now <= before) {
        total_.fetch_sub(before - now, std::memory_order_relaxed);
        bytes_[serial] = now;
        return blocks_[serial] != nullptr;
    }
    // Grow only within the budget; threads race here, and whichever comes second is told no.
    const std::size_t grown = now - before;
    std::size_t total = total_.load(std::memory_order_relaxed);
    do {
        if (budget_ != kNoBudget && (total + grown > budget_ || total + grown < total)) {
            Drop(serial);
            leftOut_[serial] = 1;
            return false;
        }
    } while (!total_.compare_exchange_weak(total, total + grown, std::memory_order_relaxed));
    bytes_[serial] = now;
    leftOut_[serial] = 0;
    return true;
}

void SampleStore::Drop(std::size_t serial) {
    blocks_[serial].reset();
    total_.fetch_sub(bytes_[serial], std::memory_order_relaxed);
    bytes_[serial] = 0;
}

std::size_t SampleStore::MemoryBytes() const {
    std::size_t bytes = TableBytes();
    for (const auto &b : blocks_)
        if (b) bytes += b->MemoryBytes();
    return bytes;
}

std::size_t SampleStore::SampleCount() const {
    std::size_t n = 0;
    for (const auto &b : blocks_)
        if (b) n += b->samples.size();
    return n;
}

std::size_t SampleStore::SegmentCount() const {
    std::size_t n = 0;
    for (const auto &b : blocks_)
        if (b)
            for (const StoredSample &smp : b->samples)
                if (smp.segmentCount != StoredSample::kEverything) n += smp.segmentCount;
    return n;
}

}  // namespace povrayfc
