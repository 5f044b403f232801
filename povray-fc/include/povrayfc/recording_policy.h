// RecordingPolicy: stop paying for recording while it cannot pay off, and start again
// when it can.
//
// Two ways a recorded frame is wasted: it came out full although the sequence went on
// (the camera, a light or the global settings changed, an unbounded object moved), or it
// was coherent but had to trace almost every sample anyway (something large moved across
// the view). After kWastedBeforePause wasted frames in a row recording pauses. A pause
// for full frames ends with the first frame whose change from the last is local; a pause
// for busy frames lasts a number of frames that doubles each time it does not pay off
// (2, 4, 8, 16), since such a frame's change is local and yet not worth following.
#ifndef POVRAYFC_RECORDING_POLICY_H
#define POVRAYFC_RECORDING_POLICY_H

#include <algorithm>

namespace povrayfc {

class RecordingPolicy {
  public:
    static constexpr int kWastedBeforePause = 2;
    // A coherent frame that traced more than this share of its samples was busy.
    static constexpr double kBusyShare = 0.9;
    static constexpr int kMaxBackoff = 16;

    bool Paused() const { return paused_; }

    // A recorded frame ended. full: traced in full although the sequence went on.
    // tracedShare: samples traced / samples taken (coherent frames).
    void AfterRecordedFrame(bool full, double tracedShare) {
        const bool busy = !full && tracedShare > kBusyShare;
        streak_ = (full || busy) ? streak_ + 1 : 0;
        if (!busy && !full) backoff_ = 1;
        if (streak_ < kWastedBeforePause) return;
        paused_ = true;
        streak_ = 0;
        if (busy) {
            backoff_ = std::min(kMaxBackoff, backoff_ * 2);
            waitFrames_ = backoff_;
        } else {
            waitFrames_ = 0;
        }
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
