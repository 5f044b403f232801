// hashes.h - the two 64-bit hashes fc-master writes into its run records. Both are stable
// across versions and machines: records outlive the program that wrote them.
#pragma once

#include <cstddef>
#include <cstdint>

namespace fc {

// FNV-1a over bytes: the run record's file contents, and frame records of fc-master versions
// before hash_words.
uint64_t hash_bytes(const void *data, size_t size, uint64_t seed = 14695981039346656037ull);

// A hash of bytes taken eight at a time (little-endian words): for frames' pixels, where
// FNV-1a's byte at a time cost fc-master 0.4 ms a 320x240 frame.
uint64_t hash_words(const void *data, size_t size);

} // namespace fc
