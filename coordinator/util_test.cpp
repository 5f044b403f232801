// util_test.cpp - unit tests of util.h's performance-minded helpers, which must keep what they
// promise while they get faster:
// - hash_words: the hash recorded for every frame (resume compares it with the files), the
//   same as the byte-by-byte definition for every length and alignment;
// - keep_freed_memory: frame-sized buffers freed and made again cost no page faults.
//
// keep_freed_memory: each case runs in a child of its own (the allocator's settings are the whole process's):
// four frame-sized buffers are made, written and freed three times, and the child reports the
// page faults of the third round. Without keep_freed_memory glibc gives them back to the
// kernel and the third round faults every page in again; the test checks that too, so that it
// would notice an allocator that never did (then it would prove nothing).
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <random>
#include <vector>

#include "check.h"
#include "freed_memory.h"
#include "hashes.h"

using namespace fc;

namespace {

const size_t kBuffers = 4;
const size_t kBytes = size_t(3686400) + 18;     // a 1280x960 Targa frame
const long kPages = long(kBuffers * kBytes / 4096);

long minor_faults()
{
    struct rusage u;
    getrusage(RUSAGE_SELF, &u);
    return u.ru_minflt;
}

// One round: the buffers made, written and freed (volatile: the compiler may not drop them).
void round_of_buffers()
{
    std::vector<unsigned char *> buffers;
    for (size_t i = 0; i < kBuffers; i++) {
        unsigned char *p = static_cast<unsigned char *>(malloc(kBytes));
        if (p == nullptr)
            _exit(3);
        memset(p, int(i + 1), kBytes);
        buffers.push_back(p);
    }
    volatile unsigned char sink = 0;
    for (unsigned char *p : buffers)
        sink = sink + p[kBytes - 1];
    for (unsigned char *p : buffers)
        free(p);
}

// The third round's page faults in a child, with or without keep_freed_memory; -1 on failure.
long third_round_faults(bool keep)
{
    int fds[2];
    if (pipe(fds) != 0)
        return -1;
    pid_t pid = fork();
    if (pid < 0)
        return -1;
    if (pid == 0) {
        close(fds[0]);
        if (keep)
            keep_freed_memory();
        round_of_buffers();
        round_of_buffers();
        long before = minor_faults();
        round_of_buffers();
        long faults = minor_faults() - before;
        _exit(write(fds[1], &faults, sizeof faults) == sizeof faults ? 0 : 4);
    }
    close(fds[1]);
    long faults = -1;
    if (read(fds[0], &faults, sizeof faults) != sizeof faults)
        faults = -1;
    close(fds[0]);
    int status = 0;
    waitpid(pid, &status, 0);
    return WIFEXITED(status) && WEXITSTATUS(status) == 0 ? faults : -1;
}

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

void test_hash_words()
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
    CHECK(differ == 0);
    CHECK(hash_words(bytes.data() + 3, 230400) == hash_words_by_definition(bytes.data() + 3, 230400));
    // A value written down from the implementation before this one (byte-by-byte loads):
    // records written by earlier versions must still verify.
    const unsigned char frame[] = "povray-fc frame";
    CHECK(hash_words(frame, sizeof frame - 1) == 0xdcc7b354d8762883ull);
    // And a change of one bit changes the hash.
    std::vector<unsigned char> other(bytes.begin(), bytes.begin() + 1000);
    uint64_t before = hash_words(other.data(), other.size());
    other[517] ^= 4;
    CHECK(hash_words(other.data(), other.size()) != before);
}

} // namespace

int main()
{
    test_hash_words();

    long without = third_round_faults(false);
    long with = third_round_faults(true);
    printf("page faults of the third round of %zu buffers of %zu bytes (%ld pages): "
           "glibc's defaults %ld, keep_freed_memory %ld\n", kBuffers, kBytes, kPages, without,
           with);
    CHECK(without >= 0 && with >= 0);
    // The defaults give the memory back: most pages fault in again (else this test is void).
    CHECK(without >= kPages / 2);
    // Kept: the buffers reuse the pages of the round before.
    CHECK(with >= 0 && with < kPages / 20);
    return check_summary("util_test");
}
