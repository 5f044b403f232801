// output_dir.h - fc-master's output directory: created and checked before anything renders,
// locked against a second master, and holding the record of the run.
//
// DIR/.fc-master/ holds, for each animation RUN written here (its frames' names without number,
// e.g. "clk.png" for clk01.png ...: several animations may share a directory):
//   lock          flock()ed while a master writes frames here (its pid inside, for the
//                 message): one master per directory;
//   RUN.manifest  what makes every frame what it is: the scene file's name, POV-Ray's
//                 resolved options that shape pixels, the renderer's version line, one
//                 "key<TAB>value" line each; a resume whose manifest differs is refused
//                 (--force starts over), so frames of two different renders never mix;
//   RUN.frames    one line per frame written, "name w2 HASH INPUTS": the hash of its stored
//                 pixels (hash_words), so a resume trusts a frame only if it decodes completely
//                 to the same pixels, and the id of its inputs (frame_inputs.h; "-": not
//                 known), so it keeps a frame only if they are as they were. Earlier versions
//                 wrote "name w1 HASH" and "name HASH" (hash_bytes), without inputs; synced at
//                 the end of the run (sync_records);
//   RUN.inputs    the frames' inputs, one line per file of each set: "ID<TAB>F<TAB>CONTENTS<TAB>
//                 path" (read, the hash of its contents) or "ID<TAB>A<TAB>-<TAB>path" (looked
//                 for, absent); a set whose lines do not give its id (cut short) is ignored.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "frame_inputs.h"

namespace fc {

typedef std::map<std::string, std::string> Manifest;

class OutputDir {
public:
    ~OutputDir();

    // Create dir and its parents, prove it writable by creating a file in it and
    // DIR/.fc-master and its lock, take the lock and read the record of `run`. False with err
    // (strerror text; another master's pid when locked).
    bool open(const std::string &dir, const std::string &run, std::string &err);

    const std::string &path() const { return dir_; }

    // The manifest of the frames already here (empty when there is none).
    const Manifest &previous() const { return previous_; }
    bool has_previous() const { return !previous_.empty(); }

    // Lines saying how `now` differs from the previous manifest (none when equal).
    std::vector<std::string> differences(const Manifest &now) const;

    // Replace the manifest; with fresh, also forget every recorded frame (--force, a new run).
    bool start_run(const Manifest &now, bool fresh, std::string &err);

    // The recorded hash of a frame file (by name), and whether it is hash_words' (else
    // hash_bytes', as recorded before); false when none is recorded.
    bool recorded(const std::string &name, uint64_t &hash, bool &words) const;

    // The recorded inputs of a frame file: false when its record has none (written by an
    // earlier version); inputs.known is false when they were not known.
    bool recorded_inputs(const std::string &name, FrameInputs &inputs) const;

    // Record a frame that is complete under its final name: its hash_words and its inputs.
    // False with err.
    bool record(const std::string &name, uint64_t hash, const FrameInputs &inputs,
                std::string &err);

    // Put the records written so far on disk (at the end of a run). Each frame file is synced
    // as it is written; its record is not, since a sync per frame costs every frame while a
    // power cut costs only the re-render of the frames whose records it lost. False with err.
    bool sync_records(std::string &err);

private:
    bool load(std::string &err);
    std::string manifest_path() const;
    std::string journal_path() const;
    std::string inputs_path() const;
    bool append(int fd, const std::string &path, const std::string &text, std::string &err);

    std::string dir_, meta_, run_;
    int lock_fd_ = -1;
    int journal_fd_ = -1;
    int inputs_fd_ = -1;
    Manifest previous_;
    struct Recorded {
        uint64_t hash;
        bool words;
        std::string inputs;     // the id of its inputs, "-" (not known), "" (none recorded)
    };
    std::map<std::string, Recorded> frames_;
    std::map<std::string, FrameInputs> inputs_;     // by id
};

} // namespace fc
