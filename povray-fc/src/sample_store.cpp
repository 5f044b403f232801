// SampleStore: memory and content counts over all blocks.
#include "povrayfc/sample_store.h"

namespace povrayfc {

std::size_t SampleStore::MemoryBytes() const {
    std::size_t bytes = sizeof(*this) + blocks_.capacity() * sizeof(blocks_[0]);
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
        if (b) n += b->segments.size() - b->deadSegments;
    return n;
}

}  // namespace povrayfc
