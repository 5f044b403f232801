// assembly.h - assembling returned tiles into frames and writing them with OpenImageIO.
//
// A frame lives in memory (its stored samples: zeros outside the render area like POV-Ray's
// own partial renders) from its first tile to its last; then it is encoded in the output
// format (a frame that came whole with the file POV-Ray's writer made of it is stored as that
// file: OpenImageIO, whose 262 libraries take 0.4 s of CPU to load, is then not needed),
// written under a temporary name in the output directory with every write, the fsync
// and the close checked and its size on disk compared with the encoded size, renamed to
// POV-Ray's name for it, recorded in the output directory's journal (output_dir.h), and its
// memory is freed. So a file under a final name is always complete, a full disk is an error
// that says so, and the master holds only the frames in flight. Frames whose pixels were
// dithered by diffusion come as unquantized values and are quantized here, once, over the
// whole frame.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "dither.h"
#include "output_dir.h"
#include "output_format.h"
#include "protocol.h"

namespace fc {

class FrameAssembly {
public:
    FrameAssembly(OutputDir &dir, const OutputFormat &format, const std::string &stem,
                  int digits, int width, int height, const std::vector<int> &frames);

    // Final path of frame index i, and its temporary path.
    std::string final_path(int index) const;
    std::string temp_path(int index) const;

    // Bytes one frame takes in the output format: exact when the format's size is fixed
    // (uncompressed Targa), else frame_bytes_bound() (exact is false).
    size_t frame_bytes(bool &exact) const;
    // No frame takes more than this in any output format, found without encoding one.
    size_t frame_bytes_bound() const;

    // Whether frame index i is already in the directory, complete and correct: it decodes
    // completely at the right size, and its pixels hash to what the journal recorded (a frame
    // the journal does not know is accepted only when `adopt`). why says what is wrong with a
    // frame that exists but is not accepted. pixels receives the decoded samples.
    bool verify(int index, bool adopt, std::string &why, std::vector<uint8_t> &pixels) const;

    // Hash of a frame's stored samples, as the journal records it (words: hash_words, else
    // hash_bytes, which journals of earlier versions hold).
    static uint64_t pixels_hash(const std::vector<uint8_t> &samples, bool words = true);

    // Remove temporary files a killed master left behind for our frames.
    void remove_stale_temps() const;

    // Copy the rectangles of one result (an encoding of frame_record.h) into frame index i
    // (allocated on first use). Only rectangles whose `keep` flag is set are copied (the
    // others arrived before). `file` is the image file POV-Ray made of a whole frame, or
    // empty: it is written as it is when it brought every pixel of the frame. `file_gamma` is
    // the gamma POV-Ray's file would record (0: not said), for an encoded frame. Returns
    // false with err on a malformed payload or an encoding that does not carry the format.
    bool put(int index, const std::vector<Rect> &rects, const std::vector<char> &keep,
             const std::string &encoding, const std::vector<uint8_t> &data,
             std::vector<uint8_t> file, double file_gamma, std::string &err);

    // Write frame index i (encode, temp name, checked writes and fsync, rename, journal) and
    // free its memory; its samples move to `samples` (for the preview). False with err; then
    // disk_full tells whether the file system ran out of space.
    bool write(int index, std::vector<uint8_t> &samples, bool &disk_full, std::string &err);

    // Frames currently held in memory.
    size_t pending() const { return frames_in_flight_.size(); }

    const OutputFormat &format() const { return format_; }

private:
    struct Pending {
        std::vector<uint8_t> samples;           // width * height * 3 stored samples
        std::vector<float> values;              // diffusion dithering: unquantized, or empty
        std::unique_ptr<Quantizer> quantizer;
        std::vector<uint8_t> file;              // POV-Ray's file of the whole frame, or empty
        double file_gamma = 0;                  // the gamma its file records (0: not said)
    };

    size_t encoded_size(bool &exact) const;
    size_t raw_bytes() const;           // a frame's samples, uncompressed

    OutputDir &dir_;
    OutputFormat format_;
    std::string stem_;
    int digits_, width_, height_;
    std::vector<int> frames_;
    std::map<int, Pending> frames_in_flight_;
    mutable bool bytes_known_ = false, bytes_exact_ = false;
    mutable size_t bytes_ = 0;
};

} // namespace fc
