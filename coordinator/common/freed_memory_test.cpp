// freed_memory_test.cpp - keep_freed_memory: frame-sized buffers freed and made again cost no
// page faults.
//
// Each case runs in a child of its own (the allocator's settings are the whole process's):
// four frame-sized buffers are made, written and freed three times, and the child reports the
// page faults of the third round. Without keep_freed_memory glibc gives them back to the
// kernel and the third round faults every page in again; the test checks that too, so that it
// would notice an allocator that never did (then it would prove nothing).
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <vector>

#include <gtest/gtest.h>

#include "freed_memory.h"

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

} // namespace

TEST(FreedMemory, FrameBuffersAreKeptForTheNextFrame)
{
    long without = third_round_faults(false);
    long with = third_round_faults(true);
    RecordProperty("faults_default", int(without));
    RecordProperty("faults_kept", int(with));
    ASSERT_TRUE(without >= 0 && with >= 0);
    // The defaults give the memory back: most pages fault in again (else this test is void).
    EXPECT_GE(without, kPages / 2);
    // Kept: the buffers reuse the pages of the round before.
    EXPECT_LT(with, kPages / 20);
}
