// The frame-coherence session: decides per frame what to re-trace and keeps what to reuse.
#include "povrayfc/frame_coherence.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <unordered_map>

#include "povrayfc/change_set.h"
#include "povrayfc/ray_recording.h"
#include "povrayfc/retrace_mask.h"

namespace povrayfc {

namespace {

// Voxels of the automatic grid. Each ray walks about the cube root of this many voxels
// per axis it crosses; more voxels mean finer dirty regions but longer walks and lists.
constexpr std::size_t kAutomaticVoxels = 32768;

// The scene's finite objects span the grid; with none, any box will do.
Box GridBounds(const SceneSignature &signature) {
    Box bounds;
    for (const ObjectSignature &object : signature.objects)
        if (!object.infinite && !object.bounds.Empty()) bounds = Union(bounds, object.bounds);
    if (bounds.Empty()) bounds = Box{Vec3{-1, -1, -1}, Vec3{1, 1, 1}};
    return bounds;
}

// Room to move: objects that leave the grid force a full frame and a new grid, so the
// grid reaches a quarter of the scene's extent beyond it on every side.
Box WithMargin(const Box &bounds) {
    const Vec3 e = bounds.Extent();
    const double m = 0.25 * std::max({e.x, e.y, e.z});
    return Box{bounds.lo - Vec3{m, m, m}, bounds.hi + Vec3{m, m, m}};
}

VoxelGrid MakeGrid(const Box &bounds, int longestAxisResolution) {
    if (longestAxisResolution <= 0) return VoxelGrid::Automatic(bounds, kAutomaticVoxels);
    const Vec3 extent = bounds.Extent();
    const double longest = std::max({extent.x, extent.y, extent.z, 1e-30});
    int res[3];
    for (int axis = 0; axis < 3; ++axis)
        res[axis] = std::max(1, int(std::ceil(longestAxisResolution * extent[axis] / longest)));
    return VoxelGrid(bounds, res[0], res[1], res[2]);
}

// Thread-local working storage of a render thread.
struct ThreadState {
    PixelRecorder recorder;
    // AA method 2 corner lists of the block being rendered, (w+1) x (h+1).
    int cornerLeft = 0, cornerTop = 0, cornerWidth = 0;
    std::vector<std::vector<std::uint32_t>> corners;
    std::vector<std::uint8_t> cornerEverything;
};
thread_local ThreadState tls;

}  // namespace

struct FrameCoherence::Sequence {
    FrameSetup setup;
    SceneSignature signature;   // of the last frame
    VoxelGrid grid;
    DependencyStore dependencies;
    std::vector<float> colours;  // 5 floats a pixel, the whole image

    Sequence(const FrameSetup &s, const SceneSignature &sig, const VoxelGrid &g)
        : setup(s), signature(sig), grid(g), dependencies(s.width, s.height),
          colours(std::size_t(s.width) * std::size_t(s.height) * 5, 0.0f) {}
};

FrameCoherence &FrameCoherence::Get() {
    static FrameCoherence session;
    return session;
}

void FrameCoherence::Reset() {
    seq_.reset();
    active_ = false;
}

void FrameCoherence::StartSequence(const FrameSetup &setup, const SceneSignature &signature) {
    Box bounds = WithMargin(GridBounds(signature));
    // An object left the grid: the new one also spans the old, where it came from.
    if (seq_) bounds = Union(bounds, seq_->grid.Bounds());
    seq_ = std::make_unique<Sequence>(setup, signature, MakeGrid(bounds, setup.gridResolution));
}

void FrameCoherence::MarkAllDirty() {
    dirty_ = DirtyMask(seq_->setup.width, seq_->setup.height);
    dirty_.SetAll();
}

// Returns why this frame cannot reuse the last one's pixels, or "" when it can.
// Sets newSequence when the stored state is of no use any more.
std::string FrameCoherence::CompareWithLastFrame(const FrameSetup &setup, const SceneSignature &signature,
                                                 bool &newSequence) {
    newSequence = true;
    if (!seq_) return "first frame";
    const FrameSetup &last = seq_->setup;
    if (setup.width != last.width || setup.height != last.height || setup.left != last.left ||
        setup.top != last.top || setup.right != last.right || setup.bottom != last.bottom ||
        setup.samplingMethod != last.samplingMethod || setup.blockSize != last.blockSize ||
        setup.optionsHash != last.optionsHash || setup.gridResolution != last.gridResolution)
        return "render settings changed";
    if (setup.sceneCameraOverride) return "camera set by the front end";
    if (signature.camera != seq_->signature.camera) return "camera changed: new sequence";
    newSequence = false;
    if (signature.lights != seq_->signature.lights) return "light sources changed";
    if (signature.global != seq_->signature.global) return "global settings or atmosphere changed";
    return "";
}

void FrameCoherence::BeginFrame(bool enabled, const FrameSetup &setup, const void *sceneKey,
                                const SceneEffects &effects) {
    const auto start = std::chrono::steady_clock::now();
    frameStart_ = start;
    traced_ = 0;
    reused_ = 0;
    current_ = FrameStats();
    current_.frame = setup.frameNumber;
    current_.clock = setup.clock;
    current_.pixels = std::uint64_t(std::max(0, setup.AreaWidth())) * std::uint64_t(std::max(0, setup.AreaHeight()));

    enabled_ = enabled;
    statsFile_ = setup.statsFile;
    maskDir_ = setup.maskDir;
    traced_mask_ = maskDir_.empty() ? DirtyMask() : DirtyMask(std::max(1, setup.width), std::max(1, setup.height));
    maskArea_[0] = setup.left;
    maskArea_[1] = setup.top;
    maskArea_[2] = setup.right;
    maskArea_[3] = setup.bottom;
    SceneSignature signature;
    const bool haveSignature = TakeSceneSignature(sceneKey, signature) && signature.complete;
    if (!enabled) {
        Reset();
        bookkeeping_ = std::chrono::steady_clock::now() - start;
        return;
    }

    // Effects fc cannot keep exact: render exactly as POV-Ray does, record nothing.
    std::string inexact;
    if (!haveSignature) inexact = "no scene signature from the parser";
    else if (!signature.inexactEffects.empty()) inexact = signature.inexactEffects.front();
    else if (effects.radiosity) inexact = "radiosity";
    else if (effects.subsurface) inexact = "subsurface scattering";
    else if (effects.jitteredAreaLight) inexact = "jittered area light";
    else if (setup.mosaicPreview) inexact = "mosaic preview";
    else if (setup.continueTrace) inexact = "continued trace";
    if (!inexact.empty()) {
        Reset();
        current_.fullReason = inexact + " (fc cannot keep it exact)";
        bookkeeping_ = std::chrono::steady_clock::now() - start;
        return;
    }

    bool newSequence = false;
    std::string reason = CompareWithLastFrame(setup, signature, newSequence);

    if (reason.empty()) {
        // Objects are matched as a multiset of signatures: what vanished dirties its old
        // bounds, what appeared its new bounds.
        std::unordered_map<std::uint64_t, std::vector<const ObjectSignature *>> before;
        for (const ObjectSignature &object : seq_->signature.objects) before[object.hash].push_back(&object);
        ChangeSet changes;
        bool anyChange = false;
        for (const ObjectSignature &object : signature.objects) {
            auto found = before.find(object.hash);
            if (found != before.end() && !found->second.empty()) {
                found->second.pop_back();
                continue;
            }
            anyChange = true;
            if (object.infinite) changes.MarkAll("an unbounded object changed");
            else if (object.hasCapsule) changes.AddBox(object.bounds, object.capsule);
            else changes.AddBox(object.bounds);
        }
        for (const auto &entry : before)
            for (const ObjectSignature *object : entry.second) {
                anyChange = true;
                if (object->infinite) changes.MarkAll("an unbounded object changed");
                else if (object->hasCapsule) changes.AddBox(object->bounds, object->capsule);
                else changes.AddBox(object->bounds);
            }
        if (anyChange && effects.photons) changes.MarkAll("photons (the photon map depends on every object)");

        DirtyResult dirty = DirtyVoxels(seq_->grid, changes);
        if (dirty.all) {
            reason = dirty.reason.empty() ? "everything changed" : dirty.reason;
            // An object outside the grid was never recorded: span the new scene.
            newSequence = !changes.AllMarked();
        } else {
            current_.dirtyVoxels = dirty.voxels.Count();
            dirty_ = seq_->dependencies.DirtyPixels(dirty.voxels);
        }
    }

    if (!reason.empty()) {
        if (newSequence) StartSequence(setup, signature);
        MarkAllDirty();
        current_.fullReason = reason;
        current_.dirtyVoxels = seq_->grid.VoxelCount();
    }
    seq_->setup = setup;
    seq_->signature = std::move(signature);
    current_.coherent = true;
    current_.voxels = seq_->grid.VoxelCount();
    active_ = true;
    bookkeeping_ = std::chrono::steady_clock::now() - start;
}

bool FrameCoherence::AnyNeedsTrace(int left, int top, int right, int bottom) const {
    for (int y = top; y <= bottom; ++y)
        for (int x = left; x <= right; ++x)
            if (dirty_.Test(x, y)) return true;
    return false;
}

bool FrameCoherence::CornerNeeded(int x, int y, int left, int top, int right, int bottom) const {
    // Corner (x, y) is used by pixels (x-1..x, y-1..y); only those inside the block count.
    for (int py = std::max(top, y - 1); py <= std::min(bottom, y); ++py)
        for (int px = std::max(left, x - 1); px <= std::min(right, x); ++px)
            if (dirty_.Test(px, py)) return true;
    return false;
}

void FrameCoherence::StoredColour(int x, int y, float rgbft[5]) const {
    const float *c = &seq_->colours[(std::size_t(y) * std::size_t(seq_->setup.width) + std::size_t(x)) * 5];
    std::copy(c, c + 5, rgbft);
}

void FrameCoherence::StoreColour(int x, int y, const float rgbft[5]) {
    float *c = &seq_->colours[(std::size_t(y) * std::size_t(seq_->setup.width) + std::size_t(x)) * 5];
    std::copy(rgbft, rgbft + 5, c);
}

void FrameCoherence::BeginRecording() {
    tls.recorder.Begin();
    StartRecordingRays(tls.recorder, seq_->grid);
}

void FrameCoherence::StopRecording() { StopRecordingRays(); }

void FrameCoherence::CommitPixel(int x, int y) {
    StopRecordingRays();
    seq_->dependencies.Commit(x, y, tls.recorder);
    if (!maskDir_.empty()) traced_mask_.Set(x, y);
}

void FrameCoherence::CommitBlock(int left, int top, int right, int bottom) {
    StopRecordingRays();
    seq_->dependencies.Commit(left, top, tls.recorder);
    tls.recorder.Begin();
    for (int y = top; y <= bottom; ++y)
        for (int x = left; x <= right; ++x)
            if (x != left || y != top) seq_->dependencies.Commit(x, y, tls.recorder);
    if (!maskDir_.empty())
        for (int y = top; y <= bottom; ++y)
            for (int x = left; x <= right; ++x) traced_mask_.Set(x, y);
}

void FrameCoherence::BeginBlockCorners(int left, int top, int right, int bottom) {
    tls.cornerLeft = left;
    tls.cornerTop = top;
    tls.cornerWidth = right - left + 2;
    const std::size_t count = std::size_t(tls.cornerWidth) * std::size_t(bottom - top + 2);
    if (tls.corners.size() < count) tls.corners.resize(count);
    for (std::size_t i = 0; i < count; ++i) tls.corners[i].clear();
    tls.cornerEverything.assign(count, 0);
}

void FrameCoherence::CommitCorner(int x, int y) {
    StopRecordingRays();
    const std::size_t i = std::size_t(y - tls.cornerTop) * std::size_t(tls.cornerWidth) + std::size_t(x - tls.cornerLeft);
    tls.corners[i] = tls.recorder.Voxels();
    tls.cornerEverything[i] = tls.recorder.Everything();
}

void FrameCoherence::AddCornerDependencies(int x, int y) {
    const std::size_t i = std::size_t(y - tls.cornerTop) * std::size_t(tls.cornerWidth) + std::size_t(x - tls.cornerLeft);
    for (std::uint32_t voxel : tls.corners[i]) tls.recorder.Add(voxel);
    if (tls.cornerEverything[i]) tls.recorder.MarkEverything();
}

void FrameCoherence::CountTraced(std::uint64_t pixels) { traced_.fetch_add(pixels, std::memory_order_relaxed); }
void FrameCoherence::CountReused(std::uint64_t pixels) { reused_.fetch_add(pixels, std::memory_order_relaxed); }

void FrameCoherence::EndFrame(std::uint64_t raysTraced) {
    const auto start = std::chrono::steady_clock::now();
    current_.rays = raysTraced;
    if (!active_) {
        // fc off or inactive: POV-Ray traced every pixel.
        current_.traced = current_.pixels;
    } else {
        current_.traced = traced_.load();
        current_.reused = reused_.load();
        current_.storeBytes = seq_->dependencies.MemoryBytes() + seq_->colours.size() * sizeof(float);
    }
    bookkeeping_ += std::chrono::steady_clock::now() - start;
    current_.bookkeepingSeconds = std::chrono::duration<double>(bookkeeping_).count();
    current_.renderSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - frameStart_).count();
    // The log line only with fc on (off must look like POV-Ray); the CSV either way,
    // so benchmarks can compare the same binary with fc off.
    if (enabled_) std::fprintf(stderr, "%s\n", current_.LogLine().c_str());
    std::string error;
    if (!statsFile_.empty() && !AppendStatsCsv(statsFile_, current_, error))
        std::fprintf(stderr, "Frame_Coherence_Stats: cannot write %s\n", error.c_str());
    if (!maskDir_.empty()) {
        // Without fc every pixel of the render area was traced.
        if (!active_)
            for (int y = maskArea_[1]; y <= maskArea_[3]; ++y)
                for (int x = maskArea_[0]; x <= maskArea_[2]; ++x) traced_mask_.Set(x, y);
        char name[32];
        std::snprintf(name, sizeof name, "/retraced%04d.png", current_.frame);
        if (!WriteRetraceMask(maskDir_ + name, traced_mask_, error))
            std::fprintf(stderr, "Frame_Coherence_Mask: cannot write %s\n", error.c_str());
    }
    last_ = current_;
}

}  // namespace povrayfc
