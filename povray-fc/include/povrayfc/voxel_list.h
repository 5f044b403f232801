// VoxelList: the byte encoding of one pixel's voxel ids, in the order they were recorded,
// built for a cheap one-pass encode (every traced pixel) and fast scanning (DirtyPixels).
//
// Block: [LEB128 count][LEB128 data bytes][control: 1 bit per entry, (count+7)/8 bytes]
//        [data][1 zero pad byte]
// Entry i holds the signed step d_i = id_i - id_{i-1} (modulo 2^32; id_{-1} = 0, so d_0 =
// id_0). Control bit 0: 1 data byte, d + 128 (d in [-128, 127]); control bit 1: 2 bytes
// little-endian, d + 32768 (d in [-32768, 32766]), or the escape 0xFFFF followed by d in
// 4 bytes. Any uint32 ids in any order (duplicates too) round-trip, in order.
//
// Why recorded order, not sorted (measured with povrayfc_bench, 64^3 grid, 1920x1080, back
// to back on the same loaded 2-vCPU VM; see README.md): the list used to be sorted so that
// it could store ascending gaps, and on a real render with fc on, committing a pixel was
// ~28% of the whole render (sort ~18%, sizing + encoding ~10%). The PixelRecorder's list is
// already unique and in the order the rays walked the voxels, so consecutive ids mostly
// differ by +-1, +-nx or +-nx*ny: signed steps are about as small as sorted gaps. Commit
// is now one pass over the ids into a thread-local scratch buffer plus one exact-size
// allocation and memcpy: 1030 -> 185 ns/pixel at ~80 entries, 2480 -> 290 ns at ~150.
// Cost: 1.674 -> 1.694 B/entry at ~80 entries, 1.502 -> 1.558 at ~150 (a new ray's first
// voxel after dedupe is far from the previous ray's last one: ~0.8 escapes/pixel at ~150
// entries vs ~0.05 sorted). DirtyPixels still decodes every entry and is now faster (see
// below); stopping a pixel's scan past the largest dirty id (tried with sorted lists, not
// adopted) would now need the largest id stored in the header.
//
// Why d + 128 / d + 32768 (offset binary) rather than zigzag (0, -1, 1, -2... -> 0, 1, 2,
// 3...): both give ranges of the same width per length (zigzag's 2-byte range is
// [-32767, 32767]), hence practically the same sizes, but offset
// binary decodes as v += z - bias[wide] (2 instructions) where zigzag needs 5. At ~80
// entries/pixel DirtyPixels took ~200 ms with sorted gaps, ~240 ms with zigzag steps, ~200
// ms with zigzag and the loop below (8 entries per control byte, no count check per
// entry), and 150-165 ms with offset binary and that loop.
//
// Why not plain LEB128 varints (the first version): a LEB128 decoder branches on each
// byte's continuation bit, and with about half the entries needing 2 bytes that branch is
// a coin flip: DirtyPixels took 275 ms vs 200 ms for sorted gaps in this format (~1.65 vs
// ~1.2 ns/entry), for only ~0-9% fewer bytes. Here entry lengths come from a control byte
// already in a register, so decoding has no data-dependent branch except the rare escape;
// the encoder likewise stores 2 bytes for every entry and advances by 1 or 2.
#ifndef POVRAYFC_VOXEL_LIST_H
#define POVRAYFC_VOXEL_LIST_H

#include <cstddef>
#include <cstdint>
#include <vector>

#include "povrayfc/varint.h"

namespace povrayfc {

// Bytes needed to encode ids (non-empty, any order).
std::size_t VoxelListSize(const std::vector<std::uint32_t> &ids);
// Encodes ids (non-empty, any order) into out (VoxelListSize(ids) bytes). Returns one past
// the last byte written.
std::uint8_t *EncodeVoxelList(const std::vector<std::uint32_t> &ids, std::uint8_t *out);
// Encodes ids[0..n) (n > 0, any order) in one pass into a thread-local scratch buffer and
// returns a copy in a new[]-allocated block of exactly VoxelListBlockSize() bytes (release
// it with delete[]). Thread-safe. This is DependencyStore::Commit's path.
std::uint8_t *NewVoxelList(const std::uint32_t *ids, std::size_t n);
// Total size of an encoded block, read from its header.
std::size_t VoxelListBlockSize(const std::uint8_t *block);
// Number of ids in an encoded block.
inline std::uint32_t VoxelListCount(const std::uint8_t *block) {
    std::uint32_t n;
    GetVarint(block, n);
    return n;
}

namespace voxel_list_detail {
// By control bit (1 or 2 data bytes): the data mask and the offset added to the step.
inline constexpr std::uint32_t kEntryMask[2] = {0xffu, 0xffffu};
inline constexpr std::uint32_t kEntryBias[2] = {0x80u, 0x8000u};
constexpr std::uint32_t kEscape = 0xffffu;  // 2-byte value announcing a 4-byte step
}  // namespace voxel_list_detail

// Calls stop = f(uint32_t id) for each id, in the order they were encoded, until f returns
// true. Returns true if f stopped the scan.
template <class F>
bool DecodeVoxelList(const std::uint8_t *block, F f) {
    namespace d = voxel_list_detail;
    std::uint32_t n, dataBytes;
    const std::uint8_t *p = GetVarint(block, n);
    p = GetVarint(p, dataBytes);
    const std::uint8_t *ctrl = p;
    const std::uint8_t *data = p + (n + 7) / 8;
    std::uint32_t v = 0;  // id_{-1} = 0: the first step is the first id
    // One entry, wide being its control bit. No data-dependent branch but the rare escape.
    auto step = [&](std::uint32_t wide) {
        // Reads one byte past a 1-byte entry; the pad byte makes that safe at the end.
        std::uint32_t z = (std::uint32_t(data[0]) | std::uint32_t(data[1]) << 8) & d::kEntryMask[wide];
        data += 1 + wide;
        if (z == d::kEscape) {
            z = (std::uint32_t(data[0]) | std::uint32_t(data[1]) << 8 | std::uint32_t(data[2]) << 16 |
                 std::uint32_t(data[3]) << 24) +
                d::kEntryBias[1];
            data += 4;
        }
        v += z - d::kEntryBias[wide];
        return f(v);
    };
    // Whole control bytes first (8 entries, no count check per entry), then the last one.
    const std::uint32_t whole = n / 8;
    for (std::uint32_t i = 0; i < whole; ++i) {
        const std::uint32_t c = ctrl[i];
        for (std::uint32_t j = 0; j < 8; ++j)
            if (step(c >> j & 1)) return true;
    }
    if (const std::uint32_t rest = n & 7) {
        const std::uint32_t c = ctrl[whole];
        for (std::uint32_t j = 0; j < rest; ++j)
            if (step(c >> j & 1)) return true;
    }
    return false;
}

}  // namespace povrayfc

#endif
