// VoxelList encoding: one pass over the ids into a thread-local scratch buffer, then one copy.
#include "povrayfc/voxel_list.h"

#include <cassert>
#include <cstring>

namespace povrayfc {

namespace {

namespace d = voxel_list_detail;

// Room kept in front of the control bytes for the two header varints, which are written
// once the data size is known, right before the control bytes.
constexpr std::size_t kHeaderRoom = 2 * kMaxVarintBytes;

// Scratch bytes one list may need: header room, control bytes, 6 data bytes per entry (all
// escapes), pad.
std::size_t ScratchBytes(std::size_t n) { return kHeaderRoom + (n + 7) / 8 + 6 * n + 1; }

void Store16(std::uint8_t *p, std::uint32_t v) {
    const std::uint8_t b[2] = {std::uint8_t(v), std::uint8_t(v >> 8)};
    std::memcpy(p, b, 2);
}

void Store32(std::uint8_t *p, std::uint32_t v) {
    const std::uint8_t b[4] = {std::uint8_t(v), std::uint8_t(v >> 8), std::uint8_t(v >> 16), std::uint8_t(v >> 24)};
    std::memcpy(p, b, 4);
}

// Control bit of step s (modulo 2^32): 0 if it fits in 1 byte.
std::uint32_t Wide(std::uint32_t s) { return s + d::kEntryBias[0] > 0xffu; }

// Writes the control bytes of ids[0..n) at ctrl, their data right after, then the pad byte.
// Returns the number of data bytes (pad excluded). Writes at most ScratchBytes(n) -
// kHeaderRoom bytes.
std::size_t EncodeBody(const std::uint32_t *ids, std::size_t n, std::uint8_t *ctrl) {
    std::uint8_t *const data0 = ctrl + (n + 7) / 8;
    std::uint8_t *data = data0;
    std::uint32_t prev = 0;  // id_{-1} = 0
    for (std::size_t i = 0; i < n; i += 8) {
        const std::size_t k = n - i < 8 ? n - i : 8;
        std::uint32_t c = 0;
        for (std::size_t j = 0; j < k; ++j) {
            const std::uint32_t s = ids[i + j] - prev;
            prev = ids[i + j];
            const std::uint32_t wide = Wide(s);
            const std::uint32_t z = s + d::kEntryBias[wide];
            c |= wide << j;
            if (z < d::kEscape) {
                // Always stores 2 bytes (a 1-byte entry's second byte is overwritten by the
                // next entry or the pad): no branch on the entry length.
                Store16(data, z);
                data += 1 + wide;
            } else {
                Store16(data, d::kEscape);
                Store32(data + 2, s);
                data += 6;
            }
        }
        *ctrl++ = std::uint8_t(c);
    }
    *data = 0;  // pad: the decoder reads one byte past a trailing 1-byte entry
    return std::size_t(data - data0);
}

// Encodes ids[0..n) into the calling thread's scratch buffer. Returns the block's first
// byte there; *size receives the block's size.
const std::uint8_t *EncodeToScratch(const std::uint32_t *ids, std::size_t n, std::size_t *size) {
    assert(n > 0 && n <= 0xffffffffu / 8);
    thread_local std::vector<std::uint8_t> scratch;
    const std::size_t need = ScratchBytes(n);
    if (scratch.size() < need) scratch.resize(need + need / 2);
    std::uint8_t *ctrl = scratch.data() + kHeaderRoom;
    const std::size_t dataBytes = EncodeBody(ids, n, ctrl);
    const int header = VarintSize(std::uint32_t(n)) + VarintSize(std::uint32_t(dataBytes));
    std::uint8_t *start = ctrl - header;
    PutVarint(PutVarint(start, std::uint32_t(n)), std::uint32_t(dataBytes));
    *size = std::size_t(header) + (n + 7) / 8 + dataBytes + 1;
    return start;
}

}  // namespace

std::size_t VoxelListSize(const std::vector<std::uint32_t> &ids) {
    assert(!ids.empty());
    std::size_t data = 0;
    std::uint32_t prev = 0;
    for (std::uint32_t id : ids) {
        const std::uint32_t s = id - prev, wide = Wide(s);
        data += s + d::kEntryBias[wide] < d::kEscape ? 1 + wide : 6;
        prev = id;
    }
    return std::size_t(VarintSize(std::uint32_t(ids.size()))) + std::size_t(VarintSize(std::uint32_t(data))) +
           (ids.size() + 7) / 8 + data + 1;
}

std::uint8_t *EncodeVoxelList(const std::vector<std::uint32_t> &ids, std::uint8_t *out) {
    std::size_t size;
    const std::uint8_t *block = EncodeToScratch(ids.data(), ids.size(), &size);
    std::memcpy(out, block, size);
    return out + size;
}

std::uint8_t *NewVoxelList(const std::uint32_t *ids, std::size_t n) {
    std::size_t size;
    const std::uint8_t *block = EncodeToScratch(ids, n, &size);
    std::uint8_t *out = new std::uint8_t[size];
    std::memcpy(out, block, size);
    return out;
}

std::size_t VoxelListBlockSize(const std::uint8_t *block) {
    std::uint32_t n, dataBytes;
    const std::uint8_t *p = GetVarint(block, n);
    p = GetVarint(p, dataBytes);
    return std::size_t(p - block) + (n + 7) / 8 + dataBytes + 1;
}

}  // namespace povrayfc
