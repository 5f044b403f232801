// parse_reads.h - the files a frame's parse read or looked for in vain: the renderer's side of
// the frame record's reads section (frame_record.h), from which fc-master's resume knows what
// each frame's picture depends on. No POV-Ray headers.
//
// Every file POV-Ray's parser reads (the scene, includes, macro files, image maps, density
// files, fonts, #fopen'd files) and every file_exists test goes through Locate_File
// (backend/support/fileutil.cpp), which asks the front end to search for it:
// FileMessageHandler::FindFilePath tries each candidate name in the current directory and then
// in each library path, and returns the first that exists. Two hooks report here (patch
// 0305): FindFilePath each candidate it finds no file at (absent), Locate_File the file it
// opened (opened). The frame channel turns the collection on when it opens, starts it afresh
// when a frame's parse starts, and takes it into the frame's record.
//
// The hooks run on the parser's thread and on the front end's, one at a time in practice;
// a mutex keeps them apart all the same. Off (no frame channel), a note costs one atomic load.
#pragma once

#include <atomic>
#include <mutex>
#include <string>
#include <unordered_set>

namespace fc {

class ParseReads {
public:
    // The renderer's one collection (one render per process).
    static ParseReads &process();

    // Collect from now on (on), or never (off: notes are dropped, and what was collected).
    void enable(bool on);
    bool enabled() const { return on_.load(std::memory_order_relaxed); }

    // A frame's parse starts: forget the last frame's files.
    void restart();

    // The parse opened and read `path`; a lookup found nothing at `path`. Paths as POV-Ray
    // formed them; each line is kept once.
    void opened(const std::string &path) { note('F', path); }
    void absent(const std::string &path) { note('A', path); }

    // The reads section so far ("F<TAB>path<LF>" and "A<TAB>path<LF>" lines, in the order
    // first met), emptied.
    std::string take();

private:
    void note(char kind, const std::string &path);

    std::atomic<bool> on_{false};
    std::mutex mutex_;
    std::string lines_;
    std::unordered_set<std::string> seen_;
};

} // namespace fc
