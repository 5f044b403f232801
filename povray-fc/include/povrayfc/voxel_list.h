// VoxelList: the byte encoding of one pixel's sorted voxel ids, built for fast scanning.
//
// Block: [LEB128 count][LEB128 data bytes][control: 1 bit per entry, (count+7)/8 bytes]
//        [data][1 zero pad byte]
// Entry i holds gap_i = id_i - id_{i-1} - 1 (id_{-1} = -1, so gap_0 = id_0): control bit 0
// means 1 data byte (gap < 256); 1 means 2 bytes little-endian (gap < 65535), or the escape
// 0xFFFF followed by the gap in 4 bytes.
//
// Why not plain LEB128 varints of the gaps (the first version; measured with
// povrayfc_bench, 64^3 grid, 1920x1080, back to back on the same machine): they are a
// little smaller (1.52 vs 1.67 bytes/entry at ~80 entries/pixel, 1.49 vs 1.50 at ~150),
// but a LEB128 decoder branches on each byte's continuation bit, and with about half the
// gaps needing 2 bytes that branch is a coin flip: DirtyPixels took 275 ms vs 200 ms
// (~1.65 vs ~1.2 ns/entry). Here entry lengths come from a control byte already in a
// register, so decoding has no data-dependent branch except the rare escape.
#ifndef POVRAYFC_VOXEL_LIST_H
#define POVRAYFC_VOXEL_LIST_H

#include <cstddef>
#include <cstdint>
#include <vector>

#include "povrayfc/varint.h"

namespace povrayfc {

// Bytes needed to encode ids (sorted ascending, unique, non-empty).
std::size_t VoxelListSize(const std::vector<std::uint32_t> &ids);
// Encodes ids into out (VoxelListSize(ids) bytes). Returns one past the last byte written.
std::uint8_t *EncodeVoxelList(const std::vector<std::uint32_t> &ids, std::uint8_t *out);
// Total size of an encoded block, read from its header.
std::size_t VoxelListBlockSize(const std::uint8_t *block);
// Number of ids in an encoded block.
inline std::uint32_t VoxelListCount(const std::uint8_t *block) {
    std::uint32_t n;
    GetVarint(block, n);
    return n;
}

// Calls stop = f(uint32_t id) for each id in ascending order until f returns true.
// Returns true if f stopped the scan.
template <class F>
bool DecodeVoxelList(const std::uint8_t *block, F f) {
    std::uint32_t n, dataBytes;
    const std::uint8_t *p = GetVarint(block, n);
    p = GetVarint(p, dataBytes);
    const std::uint8_t *ctrl = p;
    const std::uint8_t *data = p + (n + 7) / 8;
    std::uint32_t v = 0xffffffffu;  // id_{-1} = -1: the first gap is the first id
    for (std::uint32_t i = 0; i < n; i += 8) {
        std::uint32_t c = *ctrl++;
        const std::uint32_t k = n - i < 8 ? n - i : 8;
        for (std::uint32_t j = 0; j < k; ++j) {
            const std::uint32_t wide = c & 1;
            c >>= 1;
            // Reads one byte past a 1-byte entry; the pad byte makes that safe at the end.
            std::uint32_t gap =
                (std::uint32_t(data[0]) | std::uint32_t(data[1]) << 8) & (0xffu | (0xff00u & (0u - wide)));
            data += 1 + wide;
            if (gap == 0xffffu) {
                gap = std::uint32_t(data[0]) | std::uint32_t(data[1]) << 8 | std::uint32_t(data[2]) << 16 |
                      std::uint32_t(data[3]) << 24;
                data += 4;
            }
            v += gap + 1;
            if (f(v)) return true;
        }
    }
    return false;
}

}  // namespace povrayfc

#endif
