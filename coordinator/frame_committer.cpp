// frame_committer.cpp - see frame_committer.h.
#include "frame_committer.h"

#include <cerrno>
#include <cstdio>
#include <unistd.h>

#include "util.h"

namespace fc {

bool commit_frame(OutputDir &dir, const std::string &tmp, const std::string &dst,
                  const std::vector<uint8_t> &bytes, uint64_t hash, bool &disk_full,
                  std::string &err)
{
    disk_full = false;
    if (!write_file_durably(tmp, bytes.data(), bytes.size(), err)) {
        disk_full = errno == ENOSPC || errno == EDQUOT;
        return false;
    }
    // Recorded before it gets its name: a master killed in between leaves a record whose
    // file is missing or another (resume renders it again), never a complete frame under its
    // final name that resume would not recognise and render again.
    if (!dir.record(base_name(dst), hash, err)) {
        disk_full = errno == ENOSPC || errno == EDQUOT;
        unlink(tmp.c_str());
        return false;
    }
    // Only a complete file gets the final name (rename replaces a damaged one atomically).
    if (rename(tmp.c_str(), dst.c_str()) != 0) {
        sys_fail(err, "rename " + tmp + " to " + dst);
        unlink(tmp.c_str());
        return false;
    }
    if (!sync_dir(dir.path(), err)) {
        disk_full = errno == ENOSPC || errno == EDQUOT;
        return false;
    }
    return true;
}

FrameCommitter::FrameCommitter(OutputDir &dir) : dir_(dir), thread_([this] { run(); }) {}

FrameCommitter::~FrameCommitter()
{
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stop_ = true;
    }
    wake_.notify_one();
    thread_.join();
}

void FrameCommitter::submit(int index, std::string tmp, std::string dst,
                            std::vector<uint8_t> bytes, uint64_t hash)
{
    {
        std::lock_guard<std::mutex> lock(mutex_);
        queue_.push_back(Item{index, std::move(tmp), std::move(dst), std::move(bytes), hash});
        outstanding_++;
    }
    wake_.notify_one();
}

std::vector<FrameCommitter::Result> FrameCommitter::done(size_t unfinished)
{
    std::unique_lock<std::mutex> lock(mutex_);
    finished_.wait(lock, [&] { return outstanding_ - results_.size() <= unfinished; });
    std::vector<Result> out;
    out.swap(results_);
    outstanding_ -= out.size();
    return out;
}

size_t FrameCommitter::outstanding() const
{
    std::lock_guard<std::mutex> lock(mutex_);
    return outstanding_;
}

void FrameCommitter::run()
{
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
        wake_.wait(lock, [this] { return stop_ || !queue_.empty(); });
        if (queue_.empty())
            return;     // stopped, and everything queued is committed
        Item item = std::move(queue_.front());
        queue_.pop_front();
        Result r;
        r.index = item.index;
        if (failed_) {
            r.err = "not written: an earlier frame's write failed";
        } else {
            lock.unlock();
            r.ok = commit_frame(dir_, item.tmp, item.dst, item.bytes, item.hash, r.disk_full,
                                r.err);
            lock.lock();
            failed_ = !r.ok;
        }
        results_.push_back(std::move(r));
        finished_.notify_all();
    }
}

} // namespace fc
