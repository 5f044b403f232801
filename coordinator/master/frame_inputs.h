// frame_inputs.h - what a frame's picture depends on besides the options and its clock: the
// files its parse read (the scene, includes, image maps, fonts, #read data) or looked for and
// did not find (file_exists, a search along the library path), with the contents of each. A
// resume keeps a frame only when every one of them is as it was (output_setup.h), so an edit
// re-renders exactly the frames that read what changed.
//
// The renderer reports the files with each frame (the frame record's reads section,
// frame-channel/frame_record.h; every lookup of POV-Ray's parser goes through Locate_File).
// From a renderer that reports none, a frame's inputs are its scene file alone.
#pragma once

#include <sys/types.h>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace fc {

struct FrameInputs {
    struct File {
        bool read = true;           // read; false: looked for and absent
        std::string path;           // absolute
        uint64_t contents = 0;      // hash_words of its bytes when read
    };
    std::vector<File> files;
    // false: what the frame read could not be recorded (a file changed while it was
    // rendered, a name with a line break, a record cut short): never trusted on a resume
    bool known = true;

    // One id for these files and their contents (16 hex digits); "" when not known.
    std::string id() const;
};

// The files of a reads section ("F<TAB>path" and "A<TAB>path" lines; relative paths are the
// renderer's, whose directory is cwd), in order, each once. False with err on a malformed
// line, or a "U" line (a name with a line break: the inputs cannot be known).
bool parse_reads(const std::string &text, const std::string &cwd, FrameInputs &inputs,
                 std::string &err);

// Hashes of files' contents as they are now, each file read once per run (again only when its
// size, time or inode changed).
class InputHashes {
public:
    // Fill in the contents of inputs' read files; a file missing now, or changed after
    // `since` (seconds of the wall clock: the frame's parse may have read it before), makes
    // them unknown.
    void fill(FrameInputs &inputs, double since = 0);

    // The files of `recorded` that are not as they were: changed, gone, or (looked for and
    // absent then) there now. Empty when the frame may be kept.
    std::vector<std::string> changed(const FrameInputs &recorded);

private:
    struct Entry {
        dev_t dev = 0;
        ino_t ino = 0;
        off_t size = 0;
        long long mtime_ns = 0;
        uint64_t contents = 0;
    };
    // The file's hash now; false when it cannot be read. mtime: its modification time.
    bool hash(const std::string &path, uint64_t &contents, double &mtime);
    std::map<std::string, Entry> cache_;
};

} // namespace fc
