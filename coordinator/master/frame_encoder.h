// frame_encoder.h - how fc-master turns an assembled frame into its file, decided once per
// run: 8-bit Targa by fc-image-writer (POV-Ray's own writer, 2 ms to start) when the helper is
// there, everything else by OpenImageIO (fc-image.so: 262 libraries, 0.35-0.4 s of the
// master host's CPU to load, so it loads in the background and only when needed).
//
// A frame that came whole with POV-Ray's own file of it (Targa or PNG: the record's file=F)
// needs no encoding at all: sequence division then never loads OpenImageIO. The choice also
// says when OpenImageIO must load: while POV-Ray is probed when every assembled frame needs it
// (frame or hybrid division without the helper, PNG, OpenEXR), else when the first result
// without a file of its own arrives.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "output_format.h"
#include "schedule.h"

namespace fc {

class FrameEncoder {
public:
    // While POV-Ray is probed the format is not known yet: load OpenImageIO already when the
    // division assembles frames and no helper would write them (the likely Targa).
    static void preload_while_probing(Division division);

    FrameEncoder(const OutputFormat &format, Division division);

    // Where a warning goes (the message without "fc-master: warning: "); default: stderr.
    void on_warning(std::function<void(const std::string &)> warn) { warn_ = std::move(warn); }

    // Once the format is known: load OpenImageIO now when assembled frames will need it.
    void preload_for_run() const;
    // A result arrives that must be assembled (no file of its own): OpenImageIO loads now if
    // it will encode the frame.
    void result_without_file() const;
    // Whether a complete frame should stay in memory for now: OpenImageIO still loads and
    // would encode it (the master does not wait for the load while slaves wait for work).
    bool waits_for_image_io() const;

    // Encode an assembled frame (width x height stored samples) in the output format,
    // recording file_gamma (0: not said) where the format's writer would. fc-image-writer
    // failing (missing, killed) costs one warning, and OpenImageIO encodes the same pixels.
    bool encode(int width, int height, const void *samples, double file_gamma,
                std::vector<uint8_t> &out, std::string &err);

    // Bytes one frame of width x height takes in the format: exact when every frame has the
    // same size (uncompressed Targa: header, pixels and POV-Ray's footer), else an upper
    // bound. Found without encoding a frame of that size.
    size_t frame_bytes(int width, int height, bool &exact);
    // An upper bound on a frame's bytes in any format, found without encoding anything.
    size_t frame_bytes_bound(int width, int height) const;

    bool assembled_by_writer() const { return by_writer_; }

private:
    OutputFormat format_;
    Division division_;
    bool by_writer_ = false;            // 8-bit Targa and fc-image-writer is there
    bool writer_failed_ = false;
    std::function<void(const std::string &)> warn_;
};

} // namespace fc
