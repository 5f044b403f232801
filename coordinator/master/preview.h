// preview.h - a look at a long render while it runs: DIR/preview/latest.png (the frame
// finished last, full size) and DIR/preview/contact-sheet.png (every frame finished so far,
// reduced, in frame order, resumed ones included). First written kFirstWrite seconds into the
// render if its ETA leaves at least kMinTimeLeft seconds, then rewritten at most every
// kInterval seconds (and never more often than keeps the encoding under kMaxShare of the
// master's time), and brought up to date at the end when they exist (written while the render
// ran, or left by an earlier run); each written under a temporary name and renamed (a viewer
// never sees half a file). A render over sooner writes none: it is over before anyone could
// look. Two PNG encodings (one of them after the last frame) took 5% of a 3-second render's
// wall time, and the first write, which loads OpenImageIO, 0.25 s of the master host's CPU:
// 4.5% of 16 Newton frames at 1280x960 (5.5 s), for a look at frames about to be on disk.
// 8-bit PNG whatever the output format: 16-bit samples keep their high byte, OpenEXR's linear
// values are clipped and gamma-encoded (2.2) for the eye.
//
// The sheet is one image held in memory (at most about 4 megapixels whatever the frame count:
// frames are reduced by an integer factor, box-filtered); a frame is pasted in once, so the
// cost per frame is one reduction, and a write costs one PNG encoding (no row filter, zlib
// level 1: 27 ms for a 3.5-megapixel sheet).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "image_codec.h"

namespace fc {

class Preview {
public:
    static constexpr double kFirstWrite = 5.0; // seconds into the render of the first write
    static constexpr double kMinTimeLeft = 2.0; // the first write waits while less is left
    static constexpr double kInterval = 2.0;   // seconds between rewrites, at least
    // Share of the time the rewrites may take: on a 2-core host the master's CPU comes out of
    // the slaves' (a 1280x960 frame and its sheet took ~0.1 s to encode every 2 s, 5% of all
    // CPU in `perf`).
    static constexpr double kMaxShare = 0.01;

    // Turn the preview on at time now for frames of width x height with samples of type.
    void start(const std::string &dir, int width, int height, PixelType type, int frames,
               double now);
    bool on() const { return on_; }

    // Frame index i finished (or was already complete): its stored samples.
    void add(int index, const std::vector<uint8_t> &samples);

    // Write the files if something changed and they are due (force: now). `time_left`: the
    // render's estimated seconds to go (< 0: not known yet). A failure turns the preview off
    // and returns false with err (for a warning: it must never stop a render).
    bool flush(double now, bool force, std::string &err, double time_left = -1);

    // Most bytes the preview's files take on disk (uncompressed, a file and its temporary).
    double max_bytes() const;

    // Turn the preview off (its files stay as they are).
    void stop() { on_ = false; }

    const std::string &dir() const { return dir_; }

private:
    void to_rgb8(const std::vector<uint8_t> &samples, std::vector<uint8_t> &rgb) const;
    bool write_png(const std::string &name, int w, int h, const std::vector<uint8_t> &rgb,
                   std::string &err);

    bool on_ = false;
    std::string dir_;
    int width_ = 0, height_ = 0, frames_ = 0;
    PixelType type_ = PixelType::U8;
    int factor_ = 1, cols_ = 1, rows_ = 1, tw_ = 0, th_ = 0;
    std::vector<uint8_t> sheet_, latest_;
    bool dirty_ = false;
    bool written_ = false;      // the files exist (written by this run or an earlier one)
    double first_ = 0;          // when the first write is due
    double last_ = -1e9;
    double wait_ = kInterval;   // seconds until the next rewrite is due
};

} // namespace fc
