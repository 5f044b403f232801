// VoxelList encoding: sizing and writing a sorted voxel-id list into one block.
#include "povrayfc/voxel_list.h"

#include <cassert>

namespace povrayfc {

namespace {

int GapBytes(std::uint32_t gap) { return gap < 256 ? 1 : (gap < 0xffffu ? 2 : 6); }

std::size_t DataBytes(const std::vector<std::uint32_t> &ids) {
    std::size_t bytes = 0;
    std::uint32_t prev = 0xffffffffu;
    for (std::uint32_t id : ids) {
        bytes += std::size_t(GapBytes(id - prev - 1));
        prev = id;
    }
    return bytes;
}

}  // namespace

std::size_t VoxelListSize(const std::vector<std::uint32_t> &ids) {
    assert(!ids.empty());
    std::size_t data = DataBytes(ids);
    return std::size_t(VarintSize(std::uint32_t(ids.size()))) + std::size_t(VarintSize(std::uint32_t(data))) +
           (ids.size() + 7) / 8 + data + 1;
}

std::uint8_t *EncodeVoxelList(const std::vector<std::uint32_t> &ids, std::uint8_t *out) {
    assert(!ids.empty());
    std::size_t dataBytes = DataBytes(ids);
    std::uint8_t *p = PutVarint(out, std::uint32_t(ids.size()));
    p = PutVarint(p, std::uint32_t(dataBytes));
    std::uint8_t *ctrl = p;
    std::uint8_t *data = p + (ids.size() + 7) / 8;
    for (std::size_t i = 0; i < (ids.size() + 7) / 8; ++i) ctrl[i] = 0;
    std::uint32_t prev = 0xffffffffu;
    for (std::size_t i = 0; i < ids.size(); ++i) {
        assert(i == 0 || ids[i] > ids[i - 1]);
        std::uint32_t gap = ids[i] - prev - 1;
        prev = ids[i];
        if (gap < 256) {
            *data++ = std::uint8_t(gap);
            continue;
        }
        ctrl[i / 8] |= std::uint8_t(1u << (i % 8));
        if (gap < 0xffffu) {
            *data++ = std::uint8_t(gap);
            *data++ = std::uint8_t(gap >> 8);
            continue;
        }
        *data++ = 0xff;
        *data++ = 0xff;
        for (int b = 0; b < 4; ++b) *data++ = std::uint8_t(gap >> (8 * b));
    }
    *data++ = 0;  // pad: the decoder reads one byte past a trailing 1-byte entry
    return data;
}

std::size_t VoxelListBlockSize(const std::uint8_t *block) {
    std::uint32_t n, dataBytes;
    const std::uint8_t *p = GetVarint(block, n);
    p = GetVarint(p, dataBytes);
    return std::size_t(p - block) + (n + 7) / 8 + dataBytes + 1;
}

}  // namespace povrayfc
