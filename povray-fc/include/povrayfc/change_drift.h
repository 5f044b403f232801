// ChangeDrift: how far a frame's changes lie beyond those of a recent earlier frame.
//
// Most stored samples a change's cones reach are tested clean, and again the next frame,
// and the next: on Newton's cradle 29,000 samples a frame were tested and 2,500 were dirty.
// A clean sample therefore keeps, with the frame's stamp, how much wider than its margin
// the box around that frame's changed hulls could have been with every segment it tested
// still missing it (ChangeIndex::UnionClearance), and which bundles it tested
// (block_tracer.cpp). A later frame whose changes lie inside that box widened by less than
// the kept clearance cannot reach those segments, so the sample is clean without a test.
//
// The argument, with U_R and U_F the boxes around the changed hulls of frames R and F and
// SM a segment's rounding margin (SegmentMargin) against a box: a hull of F widened by its
// margin lies in U_F widened by 2 SM(U_F) (the union test's argument); a clearance c kept
// in frame R means the segment misses U_R widened by 4 SM(U_R) + c, computed, hence by
// 2 SM(U_R) + c truly (the rounding is far inside SM). So the sample is clean in F when U_F
// widened by 2 SM(U_F) lies in U_R widened by 2 SM(U_R) + c: when e + 2 (SM(U_F) - SM(U_R))
// < c, e being how far U_F juts out of U_R along any axis. SM(U_F) - SM(U_R) is at most
// 2^-19 (|c_F - c_R| + |h_F - h_R|) for centres c and half extents h (max norm), whatever
// the segment: Since() returns e plus twice that.
#ifndef POVRAYFC_CHANGE_DRIFT_H
#define POVRAYFC_CHANGE_DRIFT_H

#include <array>
#include <cstdint>
#include <limits>

#include "povrayfc/geometry.h"

namespace povrayfc {

class ChangeDrift {
  public:
    // Frames remembered: a clearance kept longer ago is tested again.
    static constexpr std::uint32_t kFrames = 64;

    // A frame whose changed hulls lie in `bounds` (finite, not empty) begins: returns its
    // stamp (never 0; 0 once stamps would wrap after 2^32 frames: keep nothing then).
    std::uint32_t Begin(const Box &bounds);
    // How far, at most, the current frame's changes reach beyond those of the frame
    // stamped `stamp` (with the margins above); +infinity for stamp 0 or a frame not among
    // the last kFrames stamped.
    double Since(std::uint32_t stamp) const {
        const Frame &f = frames_[stamp % kFrames];
        return stamp != 0 && f.stamp == stamp ? f.drift : std::numeric_limits<double>::infinity();
    }

  private:
    struct Frame {
        std::uint32_t stamp = 0;
        Box bounds;
        double drift = std::numeric_limits<double>::infinity();
    };
    std::array<Frame, kFrames> frames_;
    std::uint32_t last_ = 0;
};

// How far `now` juts out of `then` along any axis, plus twice the most the rounding margin
// of a segment can grow from `then` to `now` (see above); both finite and not empty.
double DriftBeyond(const Box &now, const Box &then);

}  // namespace povrayfc

#endif
