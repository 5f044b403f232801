// hashes_test.cpp - hash_words, the hash recorded for every frame (resume compares it with
// the files): the same as its byte-by-byte definition for every length and alignment, and the
// same value as the versions before it.
#include <cstdint>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "hashes.h"

using namespace fc;

namespace {

// hash_words by its definition: bytes taken eight at a time as little-endian words, the tail
// zero-padded, the length mixed in first.
uint64_t hash_words_by_definition(const unsigned char *p, size_t size)
{
    auto mix = [](uint64_t h, uint64_t word) {
        h ^= word;
        h *= 0x9e3779b97f4a7c15ull;
        return h ^ (h >> 32);
    };
    uint64_t h = mix(0x6672616d65730000ull, uint64_t(size));
    size_t i = 0;
    for (; i + 8 <= size; i += 8) {
        uint64_t word = 0;
        for (int b = 7; b >= 0; b--)
            word = (word << 8) | p[i + size_t(b)];
        h = mix(h, word);
    }
    uint64_t tail = 0;
    for (size_t b = size; b > i; b--)
        tail = (tail << 8) | p[b - 1];
    return mix(h, tail);
}

} // namespace

TEST(Hashes, WordsEqualTheirDefinition)
{
    std::mt19937_64 random(20261205);
    std::vector<unsigned char> bytes(230400 + 16);
    for (unsigned char &b : bytes)
        b = static_cast<unsigned char>(random());
    // Every length up to 40 at every alignment, and a 320x240 frame.
    int differ = 0;
    for (size_t offset = 0; offset < 8; offset++)
        for (size_t size = 0; size <= 40; size++)
            differ += hash_words(bytes.data() + offset, size) !=
                      hash_words_by_definition(bytes.data() + offset, size);
    EXPECT_TRUE(differ == 0);
    EXPECT_TRUE(hash_words(bytes.data() + 3, 230400) == hash_words_by_definition(bytes.data() + 3, 230400));
    // A value written down from the implementation before this one (byte-by-byte loads):
    // records written by earlier versions must still verify.
    const unsigned char frame[] = "povray-fc frame";
    EXPECT_TRUE(hash_words(frame, sizeof frame - 1) == 0xdcc7b354d8762883ull);
    // And a change of one bit changes the hash.
    std::vector<unsigned char> other(bytes.begin(), bytes.begin() + 1000);
    uint64_t before = hash_words(other.data(), other.size());
    other[517] ^= 4;
    EXPECT_TRUE(hash_words(other.data(), other.size()) != before);
}
