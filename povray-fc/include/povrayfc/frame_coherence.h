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
#include <memory>
#include <string>

#include "povrayfc/change_detection.h"
#include "povrayfc/change_index.h"
#include "povrayfc/dirty_mask.h"
#include "povrayfc/frame_plan.h"
#include "povrayfc/frame_setup.h"
#include "povrayfc/frame_stats.h"
#include "povrayfc/recording_policy.h"
#include "povrayfc/replay_policy.h"
#include "povrayfc/sample_store.h"
#include "povrayfc/scene_signature.h"
#include "povrayfc/unit_ids.h"

namespace povrayfc {

class FrameCoherence {
  public:
    // The process-wide session (POV-Ray keeps nothing else across frames).
    static FrameCoherence &Get();

    // The store's memory budget when Frame_Coherence_Memory does not set one: half of the
    // machine's memory.
    static std::size_t DefaultBudgetBytes();

    // Starts a frame. `enabled` is the Frame_Coherence option; when false the session
    // forgets everything and the frame renders exactly as in POV-Ray.
    void BeginFrame(bool enabled, const FrameSetup &setup, const void *sceneKey, const SceneEffects &effects);

    // What the render threads do this frame (valid until the next BeginFrame).
    const FramePlan &Plan() const { return plan_; }
    bool Active() const { return plan_.mode != FramePlan::Mode::kIdle; }

    // Ends the frame: statistics to the log (stderr) and the CSV file, and with a mask
    // folder set, <folder>/retraced<frame>.png (frame zero-padded to 4 digits).
    void EndFrame(std::uint64_t raysTraced);

    // The statistics of the last finished frame (for tests and tools).
    const FrameStats &LastStats() const { return last_; }

  private:
    FrameCoherence() = default;

    void Forget();
    void NewStore(const FrameSetup &setup);
    void PlanFrame(const FrameSetup &setup, const SceneSignature &signature, const SceneEffects &effects,
                   const std::string &inexact);
    // Gives this frame's units their ids (afresh when every stored sample is traced again)
    // and marks the changed ones for the render threads.
    void NumberUnits(const FrameChange &change, std::size_t unitCount, bool afresh);

    // The last frame parsed with fc on (kept while recording is paused, to see when a
    // frame can be coherent again).
    bool haveLast_ = false;
    FrameSetup lastSetup_;
    SceneSignature lastSignature_;

    std::unique_ptr<SampleStore> store_;
    ChangeIndex changes_;
    ChangeIndex translucentChanges_;  // FramePlan::translucentChanges
    std::vector<Blocker> blockers_;  // FramePlan::blockers
    ChangeDrift drift_;  // the changes of recent frames, for the clearances samples keep
    UnitIds unitIds_;
    std::vector<std::uint8_t> changedUnits_;  // by unit id: changed or vanished this frame
    std::vector<std::uint32_t> changedIds_;   // the ids set in changedUnits_
    FrameCounters counters_;
    DirtyMask tracedMask_;
    FramePlan plan_;
    RecordingPolicy policy_;
    ReplayPolicy replayPolicy_;
    bool wastedIfFull_ = false;  // this frame's recording pays off only if it is coherent

    bool enabled_ = false;
    std::string statsFile_, maskDir_;
    int maskArea_[4] = {0, 0, -1, -1};  // render area: left, top, right, bottom
    FrameStats current_, last_;
    std::chrono::steady_clock::duration bookkeeping_{};
    std::chrono::steady_clock::time_point frameStart_{};
    double fullFrameRays_ = 0.0;  // rays of the last full recorded frame
};

}  // namespace povrayfc

#endif
