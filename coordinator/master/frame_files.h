// frame_files.h - the frames on disk: their names, the check that a frame already there is
// complete and the one fc-master wrote, and storing a new one so that a file under a frame's
// final name is always complete.
//
// A frame is written as NAME.fc-tmp with every write, the fsync and the close checked and its
// size on disk compared with its bytes, recorded in the output directory's record of the run
// (output_dir.h), renamed to POV-Ray's name for it and the directory synced. So a full disk is
// an error that says so, never a short or empty frame under a final name.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "frame_inputs.h"
#include "image_codec.h"
#include "output_dir.h"
#include "output_format.h"

namespace fc {

class FrameFiles {
public:
    FrameFiles(OutputDir &dir, const OutputFormat &format, const std::string &stem, int digits,
               int width, int height, const std::vector<int> &frames);

    // Final path of frame index i, and its temporary path.
    std::string final_path(int index) const;
    std::string temp_path(int index) const;
    // The final file's name without its directory.
    std::string file_name(int index) const;

    // Whether frame index i is already in the directory, complete and correct: it decodes
    // completely at the right size, and its pixels hash to what the record says (a frame the
    // record does not know is accepted only when `adopt`). why says what is wrong with a frame
    // that exists but is not accepted. pixels receives the decoded samples.
    bool verify(int index, bool adopt, std::string &why, std::vector<uint8_t> &pixels) const;

    // Hash of a frame's stored samples, as the record holds it (words: hash_words, else
    // hash_bytes, which records of earlier versions hold).
    static uint64_t pixels_hash(const std::vector<uint8_t> &samples, bool words = true);

    // Remove temporary files a killed master left behind for our frames.
    void remove_stale_temps() const;

    // Store frame index i: bytes (its file) under the temporary name, the record of its
    // samples' hash and its inputs, the final name. False with err; then disk_full tells
    // whether the file system ran out of space.
    bool store(int index, const std::vector<uint8_t> &bytes, uint64_t samples_hash,
               const FrameInputs &inputs, bool &disk_full, std::string &err);

    OutputDir &dir() { return dir_; }
    const OutputFormat &format() const { return format_; }

private:
    OutputDir &dir_;
    OutputFormat format_;
    std::string stem_;
    int digits_, width_, height_;
    std::vector<int> frames_;
};

} // namespace fc
