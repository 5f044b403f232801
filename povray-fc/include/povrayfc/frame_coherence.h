// The frame-coherence session: state kept across the frames of one povray-fc run.
//
// Per frame, View::StartRender calls BeginFrame() once the scene is parsed. It compares
// the frame with the last one (render settings, camera, lights, global settings, the
// multiset of object signatures) and decides: re-trace only the pixels whose recorded
// rays crossed a changed voxel, or render the whole frame (with a one-line reason).
// The render threads then ask NeedsTrace() per pixel, take stored colours for the
// others, record the rays of the pixels they trace, and store every final colour.
// EndFrame() publishes statistics.
//
// Threading: BeginFrame/EndFrame run on the view's control thread, never during tracing.
// The per-pixel calls run on the render threads, each for pixels no other thread touches.
#ifndef POVRAYFC_FRAME_COHERENCE_H
#define POVRAYFC_FRAME_COHERENCE_H

#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "povrayfc/dependency_store.h"
#include "povrayfc/dirty_mask.h"
#include "povrayfc/frame_setup.h"
#include "povrayfc/frame_stats.h"
#include "povrayfc/pixel_recorder.h"
#include "povrayfc/scene_signature.h"
#include "povrayfc/voxel_grid.h"

namespace povrayfc {

class FrameCoherence {
  public:
    // The process-wide session (POV-Ray keeps nothing else across frames).
    static FrameCoherence &Get();

    // Starts a frame. `enabled` is the Frame_Coherence option; when false the session
    // forgets everything and the frame renders exactly as in POV-Ray.
    void BeginFrame(bool enabled, const FrameSetup &setup, const void *sceneKey,
                    const SceneEffects &effects);

    // True when this frame uses fc: pixels may be reused and traced pixels are recorded.
    bool Active() const { return active_; }

    // Whether pixel (x, y) must be traced this frame (dirty, or never recorded).
    bool NeedsTrace(int x, int y) const { return dirty_.Test(x, y); }
    // Whether any pixel of the inclusive rectangle must be traced (AA method 1 re-renders
    // whole blocks, whose pixels depend on each other).
    bool AnyNeedsTrace(int left, int top, int right, int bottom) const;
    // For AA method 2: whether the corner sample at (x - 0.5, y - 0.5) is needed, i.e. a
    // pixel of the block [left..right]x[top..bottom] that uses it must be traced.
    bool CornerNeeded(int x, int y, int left, int top, int right, int bottom) const;

    // The last stored colour of pixel (x, y): red, green, blue, filter, transmit.
    void StoredColour(int x, int y, float rgbft[5]) const;
    void StoreColour(int x, int y, const float rgbft[5]);

    // Recording, on the calling render thread. BeginRecording() starts a fresh list and
    // routes RecordRaySegment() into it until a Commit...() or StopRecording().
    void BeginRecording();
    void StopRecording();
    void CommitPixel(int x, int y);
    // Commits the list to the rectangle's first pixel and an empty list to its others:
    // AA method 1 re-renders whole blocks, so a block's dependencies live at one pixel.
    void CommitBlock(int left, int top, int right, int bottom);

    // AA method 2 samples pixel corners per block; a pixel depends on its 4 corners and
    // its own subdivision samples. Corner lists are kept on the thread rendering the
    // block (blocks share edge corners, and each block traces its own).
    void BeginBlockCorners(int left, int top, int right, int bottom);
    // Stops recording and keeps the list as corner (x, y)'s (the corner at x-0.5, y-0.5).
    void CommitCorner(int x, int y);
    // Adds corner (x, y)'s list to the list being recorded on this thread.
    void AddCornerDependencies(int x, int y);

    // Counts, from the render threads (relaxed atomics).
    void CountTraced(std::uint64_t pixels);
    void CountReused(std::uint64_t pixels);

    // Ends the frame: statistics to the log (stderr) and the CSV file, and with a mask
    // folder set, <folder>/retraced<frame>.png (frame zero-padded to 4 digits).
    void EndFrame(std::uint64_t raysTraced);

    // The statistics of the last finished frame (for tests and tools).
    const FrameStats &LastStats() const { return last_; }

  private:
    FrameCoherence() = default;
    struct Sequence;

    void Reset();
    void StartSequence(const FrameSetup &setup, const SceneSignature &signature);
    std::string CompareWithLastFrame(const FrameSetup &setup, const SceneSignature &signature,
                                     bool &newSequence);
    void MarkAllDirty();

    std::unique_ptr<Sequence> seq_;
    DirtyMask dirty_;
    DirtyMask traced_mask_;  // pixels traced this frame, when a mask folder is set
    bool enabled_ = false;   // the Frame_Coherence option of this frame
    bool active_ = false;
    std::string statsFile_;
    std::string maskDir_;
    int maskArea_[4] = {0, 0, -1, -1};  // render area: left, top, right, bottom
    FrameStats current_, last_;
    std::atomic<std::uint64_t> traced_{0}, reused_{0};
    std::chrono::steady_clock::duration bookkeeping_{};
    std::chrono::steady_clock::time_point frameStart_{};
};

}  // namespace povrayfc

#endif
