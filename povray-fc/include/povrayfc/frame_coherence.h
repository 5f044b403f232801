// The frame-coherence session: state kept across the frames of one povray-fc run.
//
// Per frame, View::StartRender calls BeginFrame() once the scene is parsed. It compares
// the frame with the last one (change_detection.h) and publishes a FramePlan: record
// everything (a new sequence), reuse the stored samples that no change can reach, keep
// pixels only (an effect fc cannot follow), or stay idle (fc off, or recording paused
// while frames keep coming out full). The render threads follow the plan block by block
// (block_tracer.h). EndFrame() publishes the statistics.
//
// Threading: BeginFrame/EndFrame run on the view's control thread, never during tracing;
// the plan is read-only while the render threads run.
#ifndef POVRAYFC_FRAME_COHERENCE_H
#define POVRAYFC_FRAME_COHERENCE_H

#include <chrono>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "povrayfc/change_index.h"
#include "povrayfc/dirty_mask.h"
#include "povrayfc/frame_plan.h"
#include "povrayfc/frame_setup.h"
#include "povrayfc/frame_stats.h"
#include "povrayfc/recording_policy.h"
#include "povrayfc/sample_store.h"
#include "povrayfc/scene_signature.h"

namespace povrayfc {

class FrameCoherence {
  public:
    // The process-wide session (POV-Ray keeps nothing else across frames).
    static FrameCoherence &Get();

    // The least a stored pixel takes (its final colour and one camera sample).
    static constexpr std::size_t kMinStoreBytesPerPixel = 20 + sizeof(StoredSample);

    // Starts a frame. `enabled` is the Frame_Coherence option; when false the session
    // forgets everything and the frame renders exactly as in POV-Ray. Throws
    // std::runtime_error (a one-line message) when the store for this image could not fit
    // in memory.
    void BeginFrame(bool enabled, const FrameSetup &setup, const void *sceneKey, const SceneEffects &effects);

    // What the render threads do this frame (valid until the next BeginFrame).
    const FramePlan &Plan() const { return plan_; }
    bool Active() const { return plan_.mode != FramePlan::Mode::kIdle; }

    // Ends the frame: statistics to the log (stderr) and the CSV file, and with a mask
    // folder set, <folder>/retraced<frame>.png (frame zero-padded to 4 digits).
    void EndFrame(std::uint64_t raysTraced);

    // The statistics of the last finished frame (for tests and tools).
    const FrameStats &LastStats() const { return last_; }

    // Hand-over of a tile's state between renderers (block_handover.h). Both between frames,
    // from the front end (the render threads are idle).
    // The stored blocks meeting `rects` (x0, y0, x1, y1, ... half-open) as the last frame left
    // them, appended to `out`; `frame` is that frame. False (nothing written) when there is
    // no such state: fc off, no frame yet, or a frame kept as pixels only.
    bool HandOut(const std::vector<int> &rects, std::vector<char> &out, int &frame) const;
    // Blocks handed out by another renderer, for the next frame: taken into empty slots
    // when this renderer parsed the frame they come from and the changes since can be
    // tested (see BeginFrame); refused otherwise (the statistics say why).
    void HandIn(std::vector<char> bytes);

    // Frames whose signatures are kept for hand-overs: a hand-over older than this many
    // frames is refused.
    static constexpr std::size_t kHandoverFrames = 16;

  private:
    FrameCoherence() = default;

    void Forget();
    void NewStore(const FrameSetup &setup);
    static void CheckMemory(const FrameSetup &setup);
    void PlanFrame(const FrameSetup &setup, const SceneSignature &signature, const SceneEffects &effects,
                   const std::string &inexact);
    // Takes the blocks handed in for this coherent frame (PlanFrame): each hand-over's
    // changes since its frame go into handoverChanges_.
    void AdoptHandovers(const FrameSetup &setup, const SceneSignature &signature, bool photons);

    // The last frame parsed with fc on (kept while recording is paused, to see when a
    // frame can be coherent again).
    bool haveLast_ = false;
    FrameSetup lastSetup_;
    std::shared_ptr<const SceneSignature> lastSignature_;
    // The last kHandoverFrames frames parsed with fc on, for hand-overs (oldest first).
    struct PastFrame {
        FrameSetup setup;
        std::shared_ptr<const SceneSignature> signature;
    };
    std::deque<PastFrame> past_;
    std::mutex handInMutex_;
    std::vector<std::vector<char>> handedIn_;  // bytes waiting for the next frame
    std::vector<ChangeIndex> handoverChanges_;

    std::unique_ptr<SampleStore> store_;
    ChangeIndex changes_;
    ChangeDrift drift_;  // the changes of recent frames, for the clearances samples keep
    FrameCounters counters_;
    DirtyMask tracedMask_;
    FramePlan plan_;
    RecordingPolicy policy_;
    bool wastedIfFull_ = false;  // this frame's recording pays off only if it is coherent

    bool enabled_ = false;
    std::string statsFile_, maskDir_;
    int maskArea_[4] = {0, 0, -1, -1};  // render area: left, top, right, bottom
    FrameStats current_, last_;
    std::chrono::steady_clock::duration bookkeeping_{};
    std::chrono::steady_clock::time_point frameStart_{};
    double fullFrameSeconds_ = 0.0;  // render time of the last full recorded frame
};

}  // namespace povrayfc

#endif
