// frame_committer.h - encoded frames put on disk by a thread of their own, in order, off
// fc-master's receive loop.
//
// Putting a frame on disk durably (commit_frame) waits for the disk twice: the fsync of the
// file and the fsync of the directory after the rename. At 320x240 that was about 1.1 ms a
// frame, all of it time in which the receive loop handed out no job and took no tile (51 ms
// of a 0.5 s frame division of Newton on the emulated cluster). The thread does the same
// steps in the same order, one frame after another; the loop goes on and collects what was
// committed (done()). After a failed commit nothing more is written (the frames queued behind
// it are dropped, their temporary files never made), as one POV-Ray process stops at its
// first failed write.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "output_dir.h"

namespace fc {

// Write bytes under tmp (checked writes, fsync, its size on disk compared), record name's
// hash in dir's journal, rename tmp to dst and fsync the directory: a file under a final name
// is always complete and recorded. False with err (the temporary file removed); disk_full
// tells whether the file system ran out of space.
bool commit_frame(OutputDir &dir, const std::string &tmp, const std::string &dst,
                  const std::vector<uint8_t> &bytes, uint64_t hash, bool &disk_full,
                  std::string &err);

class FrameCommitter {
public:
    struct Result {
        int index = -1;
        bool ok = false;
        bool disk_full = false;
        std::string err;
    };

    // dir's journal is written by the committer's thread only from now until the destructor.
    explicit FrameCommitter(OutputDir &dir);
    ~FrameCommitter();      // commits what is queued, then joins the thread

    void submit(int index, std::string tmp, std::string dst, std::vector<uint8_t> bytes,
                uint64_t hash);
    // The commits finished since the last call, in submission order, once at most
    // `unfinished` of the submitted frames are still to be committed (waiting till then).
    std::vector<Result> done(size_t unfinished);
    // Frames submitted and not yet returned by done().
    size_t outstanding() const;

private:
    struct Item {
        int index;
        std::string tmp, dst;
        std::vector<uint8_t> bytes;
        uint64_t hash;
    };
    void run();

    OutputDir &dir_;
    mutable std::mutex mutex_;
    std::condition_variable wake_, finished_;
    std::deque<Item> queue_;
    std::vector<Result> results_;
    size_t outstanding_ = 0;
    bool failed_ = false, stop_ = false;
    std::thread thread_;
};

} // namespace fc
