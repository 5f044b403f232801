// RecordingPolicy: stop paying for recording while frames keep coming out full (a moving
// camera, lights that change every frame), and start again when a frame can be coherent.
#ifndef POVRAYFC_RECORDING_POLICY_H
#define POVRAYFC_RECORDING_POLICY_H

namespace povrayfc {

class RecordingPolicy {
  public:
    // Consecutive full frames, after the first of a sequence, before recording pauses.
    static constexpr int kFullFramesBeforePause = 2;

    bool Paused() const { return paused_; }

    // A recorded frame ended; `wasted` when its recording cannot have paid off: it was
    // traced in full although the sequence went on (camera, lights or global settings
    // changed, an unbounded object moved...).
    void AfterRecordedFrame(bool wasted) {
        streak_ = wasted ? streak_ + 1 : 0;
        if (streak_ >= kFullFramesBeforePause) paused_ = true;
    }
    // While paused: this frame's change from the last one is local, so the next frame
    // can reuse what this one records.
    void Resume() {
        paused_ = false;
        streak_ = 0;
    }
    void Reset() { *this = RecordingPolicy(); }

  private:
    bool paused_ = false;
    int streak_ = 0;
};

}  // namespace povrayfc

#endif
