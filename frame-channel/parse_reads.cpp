// parse_reads.cpp - the files a frame's parse read or looked for in vain (see parse_reads.h).
#include "frame-channel/parse_reads.h"

#include <algorithm>

namespace fc {

ParseReads &ParseReads::process()
{
    static ParseReads reads;
    return reads;
}

void ParseReads::enable(bool on)
{
    std::lock_guard<std::mutex> lock(mutex_);
    on_.store(on, std::memory_order_relaxed);
    lines_.clear();
    seen_.clear();
}

void ParseReads::restart()
{
    std::lock_guard<std::mutex> lock(mutex_);
    lines_.clear();
    seen_.clear();
}

void ParseReads::note(char kind, const std::string &path)
{
    if (!enabled() || path.empty())
        return;
    std::string line;
    line.reserve(path.size() + 3);
    // A line break in a name would end its line early, and what follows could pass for a
    // line of its own: the name goes in a 'U' line instead, its breaks made spaces (for the
    // message alone), and the frame's inputs cannot be known.
    bool unsayable = path.find('\n') != std::string::npos;
    line += unsayable ? 'U' : kind;
    line += '\t';
    line += path;
    if (unsayable)
        std::replace(line.begin(), line.end(), '\n', ' ');
    line += '\n';
    std::lock_guard<std::mutex> lock(mutex_);
    // A macro of an include file opens the file at every call: one line for all of them.
    if (seen_.insert(line).second)
        lines_ += line;
}

std::string ParseReads::take()
{
    std::lock_guard<std::mutex> lock(mutex_);
    std::string out;
    out.swap(lines_);
    seen_.clear();
    return out;
}

} // namespace fc
