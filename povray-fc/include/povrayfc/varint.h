// LEB128 unsigned varints: the byte encoding of the dependency store's voxel-id deltas.
#ifndef POVRAYFC_VARINT_H
#define POVRAYFC_VARINT_H

#include <cassert>
#include <cstdint>

namespace povrayfc {

// Longest encoding of a uint32_t (5 groups of 7 bits).
constexpr int kMaxVarintBytes = 5;

// Writes v as 7-bit groups, least significant first, high bit set on all but the last
// byte. Returns the position after the last byte written (at most kMaxVarintBytes).
inline std::uint8_t *PutVarint(std::uint8_t *out, std::uint32_t v) {
    while (v >= 0x80) {
        *out++ = std::uint8_t(v | 0x80);
        v >>= 7;
    }
    *out++ = std::uint8_t(v);
    return out;
}

inline int VarintSize(std::uint32_t v) {
    int n = 1;
    while (v >= 0x80) {
        v >>= 7;
        ++n;
    }
    return n;
}

// Reads one varint written by PutVarint. The input is trusted (written by this library);
// the one-byte case comes first because most voxel-id deltas are < 128.
inline const std::uint8_t *GetVarint(const std::uint8_t *in, std::uint32_t &v) {
    std::uint32_t b = *in++;
    if (b < 0x80) {
        v = b;
        return in;
    }
    std::uint32_t result = b & 0x7f;
    int shift = 7;
    do {
        assert(shift <= 28);
        b = *in++;
        result |= (b & 0x7f) << shift;
        shift += 7;
    } while (b >= 0x80);
    v = result;
    return in;
}

}  // namespace povrayfc

#endif
