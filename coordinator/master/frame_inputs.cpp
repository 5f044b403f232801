// frame_inputs.cpp - the files a frame depends on (see frame_inputs.h).
#include "frame_inputs.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <set>

#include "files.h"
#include "hashes.h"
#include "text.h"

namespace fc {

std::string FrameInputs::id() const
{
    if (!known)
        return "";
    std::string listing;
    for (const File &f : files)
        listing += strf("%c\t%016llx\t%s\n", f.read ? 'F' : 'A',
                        (unsigned long long)f.contents, f.path.c_str());
    return strf("%016llx", (unsigned long long)hash_words(listing.data(), listing.size()));
}

bool parse_reads(const std::string &text, const std::string &cwd, FrameInputs &inputs,
                 std::string &err)
{
    std::set<std::string> seen;
    size_t pos = 0;
    while (pos < text.size()) {
        size_t nl = text.find('\n', pos);
        std::string line = text.substr(pos, nl == std::string::npos ? std::string::npos : nl - pos);
        pos = nl == std::string::npos ? text.size() : nl + 1;
        if (line.empty())
            continue;
        if (line.size() >= 2 && line[0] == 'U' && line[1] == '\t') {
            err = "the name of a file it read or looked for has a line break (" +
                  line.substr(2) + "): its inputs cannot be recorded, and a resume renders "
                  "it again";
            return false;
        }
        if (line.size() < 3 || (line[0] != 'F' && line[0] != 'A') || line[1] != '\t') {
            err = "malformed line in the files a frame read: " + line;
            return false;
        }
        FrameInputs::File f;
        f.read = line[0] == 'F';
        f.path = line.substr(2);
        if (f.path[0] != '/')
            f.path = cwd + "/" + f.path;
        if (seen.insert(std::string(1, line[0]) + f.path).second)
            inputs.files.push_back(f);
    }
    return true;
}

bool InputHashes::hash(const std::string &path, uint64_t &contents, double &mtime)
{
    struct stat st;
    int fd = open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0)
        return false;
    if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        close(fd);
        return false;
    }
    mtime = double(st.st_mtim.tv_sec) + double(st.st_mtim.tv_nsec) * 1e-9;
    long long mtime_ns = (long long)st.st_mtim.tv_sec * 1000000000LL + st.st_mtim.tv_nsec;
    auto it = cache_.find(path);
    if (it != cache_.end() && it->second.dev == st.st_dev && it->second.ino == st.st_ino &&
        it->second.size == st.st_size && it->second.mtime_ns == mtime_ns) {
        close(fd);
        contents = it->second.contents;
        return true;
    }
    std::string bytes;
    bool ok = true;
    if (st.st_size > 0) {
        void *map = mmap(nullptr, size_t(st.st_size), PROT_READ, MAP_PRIVATE, fd, 0);
        ok = map != MAP_FAILED;
        if (ok) {
            contents = hash_words(map, size_t(st.st_size));
            munmap(map, size_t(st.st_size));
        }
    } else {
        contents = hash_words("", 0);
    }
    close(fd);
    if (!ok)
        return false;
    cache_[path] = Entry{st.st_dev, st.st_ino, st.st_size, mtime_ns, contents};
    return true;
}

void InputHashes::fill(FrameInputs &inputs, double since)
{
    for (FrameInputs::File &f : inputs.files) {
        if (!f.read)
            continue;
        double mtime = 0;
        if (!hash(f.path, f.contents, mtime) || (since > 0 && mtime >= since))
            inputs.known = false;
    }
}

std::vector<std::string> InputHashes::changed(const FrameInputs &recorded)
{
    std::vector<std::string> out;
    if (!recorded.known)
        return {"(what the frame read could not be recorded)"};
    for (const FrameInputs::File &f : recorded.files) {
        uint64_t contents = 0;
        double mtime = 0;
        bool there = hash(f.path, contents, mtime);
        if (f.read ? !there || contents != f.contents : file_exists(f.path))
            out.push_back(f.path);
    }
    return out;
}

} // namespace fc
