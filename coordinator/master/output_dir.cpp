// output_dir.cpp - the output directory, its lock and the record of the run (see output_dir.h).
#include "output_dir.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cinttypes>
#include <cstdio>
#include <cstring>
#include <sstream>

#include "durable_write.h"
#include "files.h"
#include "text.h"

namespace fc {

namespace {

const char *const kMetaDir = ".fc-master";

std::string one_line(const std::string &s)
{
    std::string out;
    for (char c : s)
        out += (c == '\n' || c == '\r' || c == '\t') ? ' ' : c;
    return out;
}

} // namespace

OutputDir::~OutputDir()
{
    if (journal_fd_ >= 0)
        close(journal_fd_);
    if (inputs_fd_ >= 0)
        close(inputs_fd_);
    if (lock_fd_ >= 0)
        close(lock_fd_);    // releases the lock
}

bool OutputDir::open(const std::string &dir, const std::string &run, std::string &err)
{
    dir_ = dir;
    run_ = run;
    std::string why;
    if (!make_dirs(dir, why)) {
        err = "output directory " + dir + ": " + why;
        return false;
    }
    // The frames go into dir itself: a file is created there (its record's folder may be
    // writable where dir is not, another file system mounted on it).
    std::string probe = dir + strf("/.fc-master-write-test-%d", int(getpid()));
    int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd < 0) {
        sys_fail(why, "create " + probe);
        err = "output directory " + dir + " is not writable: " + why;
        return false;
    }
    close(fd);
    unlink(probe.c_str());
    meta_ = dir + "/" + kMetaDir;
    if (mkdir(meta_.c_str(), 0755) != 0 && errno != EEXIST) {
        sys_fail(why, "mkdir " + meta_);
        err = "output directory " + dir + " is not writable: " + why;
        return false;
    }
    std::string lock = meta_ + "/lock";
    lock_fd_ = ::open(lock.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (lock_fd_ < 0) {
        sys_fail(why, "open " + lock);
        err = "output directory " + dir + " is not writable: " + why;
        return false;
    }
    if (flock(lock_fd_, LOCK_EX | LOCK_NB) != 0) {
        if (errno != EWOULDBLOCK)
            return sys_fail(err, "flock " + lock);
        char buf[32] = "";
        ssize_t n = pread(lock_fd_, buf, sizeof buf - 1, 0);
        int pid = n > 0 ? atoi(buf) : 0;
        err = strf("another fc-master%s is writing frames into %s: wait for it to finish, or use "
                   "another output directory", pid > 0 ? strf(" (pid %d)", pid).c_str() : "",
                   dir.c_str());
        close(lock_fd_);
        lock_fd_ = -1;
        return false;
    }
    std::string pid = strf("%d\n", int(getpid()));
    if (ftruncate(lock_fd_, 0) != 0 || pwrite(lock_fd_, pid.data(), pid.size(), 0) != ssize_t(pid.size())) {
        sys_fail(why, "write " + lock);
        err = "output directory " + dir + " is not writable: " + why;
        return false;
    }
    return load(err);
}

bool OutputDir::load(std::string &err)
{
    std::string text;
    std::string path = manifest_path();
    if (file_exists(path)) {
        if (!read_text(path, text, err))
            return false;
        std::istringstream in(text);
        std::string line;
        while (std::getline(in, line)) {
            size_t tab = line.find('\t');
            if (tab != std::string::npos)
                previous_[line.substr(0, tab)] = line.substr(tab + 1);
        }
    }
    path = journal_path();
    if (file_exists(path)) {
        if (!read_text(path, text, err))
            return false;
        // A line cut short by a full disk or a crash names no frame: lines are checked whole.
        std::istringstream in(text);
        std::string line;
        auto hex16 = [](const std::string &t, uint64_t &v) {
            char *end = nullptr;
            v = strtoull(t.c_str(), &end, 16);
            return t.size() == 16 && end && *end == '\0';
        };
        while (std::getline(in, line)) {
            size_t sp = line.rfind(' ');
            if (sp == std::string::npos)
                continue;
            std::string last = line.substr(sp + 1), head = line.substr(0, sp);
            uint64_t h = 0;
            // "name w2 HASH INPUTS" (a frame's name ends in its extension, never in " w1")
            size_t sp2 = head.rfind(' ');
            if (sp2 != std::string::npos && ends_with(head.substr(0, sp2), " w2") &&
                hex16(head.substr(sp2 + 1), h) && (last == "-" || last.size() == 16)) {
                frames_[head.substr(0, sp2 - 3)] = Recorded{h, true, last};
                continue;
            }
            if (!hex16(last, h))
                continue;
            bool words = ends_with(head, " w1");
            if (words)
                head.resize(head.size() - 3);
            frames_[head] = Recorded{h, words, ""};
        }
    }
    path = inputs_path();
    if (file_exists(path)) {
        if (!read_text(path, text, err))
            return false;
        std::map<std::string, FrameInputs> sets;
        std::istringstream in(text);
        std::string line;
        while (std::getline(in, line)) {
            // ID TAB F|A TAB CONTENTS|- TAB path
            size_t t1 = line.find('\t'), t2 = line.find('\t', t1 + 1),
                   t3 = line.find('\t', t2 == std::string::npos ? t2 : t2 + 1);
            if (t1 != 16 || t2 != 18 || t3 == std::string::npos)
                continue;
            FrameInputs::File f;
            f.read = line[17] == 'F';
            f.contents = strtoull(line.substr(19, t3 - 19).c_str(), nullptr, 16);
            f.path = line.substr(t3 + 1);
            sets[line.substr(0, 16)].files.push_back(f);
        }
        for (auto &kv : sets)
            if (kv.second.id() == kv.first)
                inputs_[kv.first] = kv.second;
    }
    return true;
}

std::vector<std::string> OutputDir::differences(const Manifest &now) const
{
    std::vector<std::string> out;
    for (auto &kv : now) {
        auto it = previous_.find(kv.first);
        if (it == previous_.end())
            out.push_back(kv.first + " is new: " + kv.second);
        else if (it->second != kv.second)
            out.push_back(kv.first + ": " + it->second + " -> " + kv.second);
    }
    for (auto &kv : previous_)
        if (!now.count(kv.first))
            out.push_back(kv.first + " is gone (was " + kv.second + ")");
    return out;
}

bool OutputDir::start_run(const Manifest &now, bool fresh, std::string &err)
{
    std::string text;
    for (auto &kv : now)
        text += one_line(kv.first) + "\t" + one_line(kv.second) + "\n";
    std::string path = manifest_path(), tmp = path + ".tmp";
    if (!write_file_durably(tmp, text.data(), text.size(), err))
        return false;
    if (rename(tmp.c_str(), path.c_str()) != 0) {
        unlink(tmp.c_str());
        return sys_fail(err, "rename " + tmp);
    }
    previous_ = now;
    std::string journal = journal_path();
    int flags = O_RDWR | O_CREAT | O_APPEND | O_CLOEXEC | (fresh ? O_TRUNC : 0);
    journal_fd_ = ::open(journal.c_str(), flags, 0644);
    if (journal_fd_ < 0)
        return sys_fail(err, "open " + journal);
    std::string inputs = inputs_path();
    inputs_fd_ = ::open(inputs.c_str(), flags, 0644);
    if (inputs_fd_ < 0)
        return sys_fail(err, "open " + inputs);
    if (fresh) {
        frames_.clear();
        inputs_.clear();
    }
    // A line cut short (a full disk) must not run into the next run's first line.
    struct stat st;
    char last = '\n';
    for (int fd : {journal_fd_, inputs_fd_})
        if (fstat(fd, &st) == 0 && st.st_size > 0 && pread(fd, &last, 1, st.st_size - 1) == 1 &&
            last != '\n' && write(fd, "\n", 1) != 1)
            return sys_fail(err, "write " + (fd == journal_fd_ ? journal : inputs));
    return true;
}

std::string OutputDir::manifest_path() const
{
    return meta_ + "/" + run_ + ".manifest";
}

std::string OutputDir::journal_path() const
{
    return meta_ + "/" + run_ + ".frames";
}

std::string OutputDir::inputs_path() const
{
    return meta_ + "/" + run_ + ".inputs";
}

bool OutputDir::recorded_inputs(const std::string &name, FrameInputs &inputs) const
{
    auto it = frames_.find(name);
    if (it == frames_.end() || it->second.inputs.empty())
        return false;
    auto set = inputs_.find(it->second.inputs);
    if (set == inputs_.end()) {
        inputs = FrameInputs();
        inputs.known = false;   // "-", or a set cut short
    } else {
        inputs = set->second;
    }
    return true;
}

bool OutputDir::append(int fd, const std::string &path, const std::string &text,
                       std::string &err)
{
    ssize_t n = write(fd, text.data(), text.size());
    if (n != ssize_t(text.size())) {
        if (n >= 0)
            errno = ENOSPC;
        return sys_fail(err, "write " + path);
    }
    return true;
}

bool OutputDir::recorded(const std::string &name, uint64_t &hash, bool &words) const
{
    auto it = frames_.find(name);
    if (it == frames_.end())
        return false;
    hash = it->second.hash;
    words = it->second.words;
    return true;
}

bool OutputDir::record(const std::string &name, uint64_t hash, const FrameInputs &inputs,
                       std::string &err)
{
    std::string id = inputs.id();
    if (!id.empty() && !inputs_.count(id)) {
        std::string lines;
        for (const FrameInputs::File &f : inputs.files)
            lines += id + (f.read ? strf("\tF\t%016llx\t", (unsigned long long)f.contents)
                                  : std::string("\tA\t-\t")) +
                     one_line(f.path) + "\n";
        if (!append(inputs_fd_, inputs_path(), lines, err))
            return false;
        inputs_[id] = inputs;
    }
    std::string line = strf("%s w2 %016" PRIx64 " %s\n", name.c_str(), hash,
                            id.empty() ? "-" : id.c_str());
    if (!append(journal_fd_, journal_path(), line, err))
        return false;
    frames_[name] = Recorded{hash, true, id.empty() ? "-" : id};
    return true;
}

bool OutputDir::sync_records(std::string &err)
{
    if (inputs_fd_ >= 0 && fdatasync(inputs_fd_) != 0)
        return sys_fail(err, "fdatasync " + inputs_path());
    if (journal_fd_ < 0 || fdatasync(journal_fd_) == 0)
        return true;
    return sys_fail(err, "fdatasync " + journal_path());
}

} // namespace fc
