// hashes.cpp - the run records' hashes (see hashes.h).
#include "hashes.h"

#include <endian.h>

#include <cstring>

namespace fc {

uint64_t hash_bytes(const void *data, size_t size, uint64_t h)
{
    const unsigned char *p = static_cast<const unsigned char *>(data);
    for (size_t i = 0; i < size; i++) {
        h ^= p[i];
        h *= 1099511628211ull;
    }
    return h;
}

uint64_t hash_words(const void *data, size_t size)
{
    const unsigned char *p = static_cast<const unsigned char *>(data);
    auto mix = [](uint64_t h, uint64_t word) {
        h ^= word;
        h *= 0x9e3779b97f4a7c15ull;
        return h ^ (h >> 32);
    };
    uint64_t h = mix(0x6672616d65730000ull, uint64_t(size));   // "frames", then the length
    size_t i = 0;
    for (; i + 8 <= size; i += 8) {
        // The eight bytes as a little-endian word on every machine: one load (GCC compiled
        // the byte-by-byte composition into a loop of eight loads and shifts per word).
        uint64_t word;
        memcpy(&word, p + i, sizeof word);
        h = mix(h, le64toh(word));
    }
    // The last size % 8 bytes, zero-padded: the length, mixed first, tells the padding from
    // zero bytes.
    uint64_t tail = 0;
    for (size_t b = size; b > i; b--)
        tail = (tail << 8) | p[b - 1];
    return mix(h, tail);
}

} // namespace fc
