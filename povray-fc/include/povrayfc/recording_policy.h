// RecordingPolicy: stop paying for recording while it cannot pay off, and start again
// when it can.
//
// Two ways a recorded frame is wasted: it came out full although the sequence went on
// (the camera, a light or the global settings changed, an unbounded object moved), or it
// was coherent but had to trace almost every sample anyway (something large moved across
// the view). A full frame pauses recording at once, until the first frame whose change
// from the last is local: that frame resumes with the record the full frame left
// (FrameCoherence keeps it), so a single cut costs its one full frame and no more, and
// frames that stay full (a camera moving on, an object around the camera) are not
// recorded after the first.
// Busy frames pause after kBusyBeforePause of them in a row, for a number of frames that
// doubles each time recording does not pay off (2, 4, 8, 16), since such a frame's change
// is local and yet not worth following.
#ifndef POVRAYFC_RECORDING_POLICY_H
#define POVRAYFC_RECORDING_POLICY_H

#include <algorithm>

namespace povrayfc {

class RecordingPolicy {
  public:
    static constexpr int kBusyBeforePause = 2;
    // A coherent frame that did more than this share of a full frame's work (WorkShare) was
    // busy: what it saved no longer covers recording and the dirty test (about 15% of the
    // CPU of such a frame in Debian's l_o, where 80% of the samples are traced every frame).
    static constexpr double kBusyShare = 0.8;
    static constexpr int kMaxBackoff = 16;

    // Above this share of samples traced, a coherent frame's rays are weighed too.
    static constexpr double kRaysWeighedFrom = 0.5;

    bool Paused() const { return paused_; }

    // The share of a full frame's work a coherent frame did: its samples traced / taken,
    // or, once that is over kRaysWeighedFrom, its rays against the sequence's last full
    // recorded frame's, if larger. Samples differ in cost: a sample through glass or a
    // mirror traces many rays, one that hits a wall few. Counts, not time: the same frames
    // pause at the same place in every run, whatever else the machine is doing.
    static double WorkShare(double samplesShare, double rays, double fullFrameRays) {
        if (samplesShare <= kRaysWeighedFrom || !(fullFrameRays > 0.0)) return samplesShare;
        return std::max(samplesShare, rays / fullFrameRays);
    }

    // A coherent recorded frame, or a wasted full one, ended (not a sequence's first frame).
    // full: traced in full although the sequence went on. tracedShare: WorkShare (coherent
    // frames).
    void AfterRecordedFrame(bool full, double tracedShare) {
        if (full) {
            paused_ = true;
            streak_ = 0;
            waitFrames_ = 0;
            return;
        }
        if (tracedShare <= kBusyShare) {
            streak_ = 0;
            backoff_ = 1;
            return;
        }
        if (++streak_ < kBusyBeforePause) return;
        paused_ = true;
        streak_ = 0;
        backoff_ = std::min(kMaxBackoff, backoff_ * 2);
        waitFrames_ = backoff_;
    }

    // While paused, at the start of a frame: whether recording resumes with it. local:
    // its change from the last frame is local (camera, lights, globals unchanged).
    bool ResumeWith(bool local) {
        if (!local) return false;
        if (waitFrames_ > 0) {
            --waitFrames_;
            return false;
        }
        paused_ = false;
        return true;
    }
    void Reset() { *this = RecordingPolicy(); }

  private:
    bool paused_ = false;
    int streak_ = 0;
    int backoff_ = 1;
    int waitFrames_ = 0;
};

}  // namespace povrayfc

#endif
