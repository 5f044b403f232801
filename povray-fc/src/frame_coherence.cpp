// The frame-coherence session: decides per frame what the render threads reuse and record.
#include "povrayfc/frame_coherence.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include <unistd.h>

#include "povrayfc/change_detection.h"
#include "povrayfc/effect_policy.h"
#include "povrayfc/retrace_mask.h"

namespace povrayfc {

namespace {

std::size_t BlockCount(const FrameSetup &s) {
    const std::size_t bs = std::size_t(std::max(1, s.blockSize));
    const std::size_t w = std::size_t(std::max(0, s.AreaWidth())), h = std::size_t(std::max(0, s.AreaHeight()));
    return ((w + bs - 1) / bs) * ((h + bs - 1) / bs);
}

}  // namespace

FrameCoherence &FrameCoherence::Get() {
    static FrameCoherence session;
    return session;
}

void FrameCoherence::Forget() {
    fullFrameRays_ = 0.0;
    store_.reset();
    haveLast_ = false;
    policy_.Reset();
    replayPolicy_.Reset();
}

std::size_t FrameCoherence::DefaultBudgetBytes() {
    const double pages = double(sysconf(_SC_PHYS_PAGES)), pageSize = double(sysconf(_SC_PAGESIZE));
    if (!(pages > 0 && pageSize > 0)) return std::size_t(1) << 30;
    return std::size_t(0.5 * pages * pageSize);
}

// A store within the budget (Frame_Coherence_Memory, or half of the machine's memory):
// past it, blocks are traced in full rather than the process running out of memory.
void FrameCoherence::NewStore(const FrameSetup &setup) {
    const std::size_t budget = setup.memoryBudgetBytes > 0 ? std::size_t(setup.memoryBudgetBytes) : DefaultBudgetBytes();
    store_ = std::make_unique<SampleStore>(BlockCount(setup), budget);
}

void FrameCoherence::BeginFrame(bool enabled, const FrameSetup &setup, const void *sceneKey,
                                const SceneEffects &effects) {
    const auto start = std::chrono::steady_clock::now();
    frameStart_ = start;
    counters_.Reset();
    current_ = FrameStats();
    current_.frame = setup.frameNumber;
    current_.clock = setup.clock;
    current_.pixels = std::uint64_t(std::max(0, setup.AreaWidth())) * std::uint64_t(std::max(0, setup.AreaHeight()));
    enabled_ = enabled;
    statsFile_ = setup.statsFile;
    maskDir_ = setup.maskDir;
    maskArea_[0] = setup.left;
    maskArea_[1] = setup.top;
    maskArea_[2] = setup.right;
    maskArea_[3] = setup.bottom;
    tracedMask_ = maskDir_.empty() ? DirtyMask() : DirtyMask(std::max(1, setup.width), std::max(1, setup.height));
    changes_ = ChangeIndex();
    translucentChanges_ = ChangeIndex();
    plan_ = FramePlan();
    plan_.counters = &counters_;
    plan_.tracedMask = maskDir_.empty() ? nullptr : &tracedMask_;

    SceneSignature signature;
    const bool haveSignature = TakeSceneSignature(sceneKey, signature) && signature.complete;
    if (!enabled) {
        Forget();
    } else if (!haveSignature || setup.mosaicPreview || setup.continueTrace) {
        // Nothing to compare with, or pixels traced in an order fc does not follow.
        Forget();
        current_.fullReason = !haveSignature ? "no scene signature from the parser"
                                             : (setup.mosaicPreview ? "mosaic preview" : "continued trace");
        current_.fullReason += " (fc cannot keep it exact)";
    } else {
        // Effects fc cannot follow ray by ray (the parser's and the render side's view
        // of them together): pixels are kept, not samples.
        auto note = [&](bool used, const char *name) {
            if (used && std::find(signature.inexactEffects.begin(), signature.inexactEffects.end(), name) ==
                            signature.inexactEffects.end())
                signature.inexactEffects.push_back(name);
        };
        note(effects.radiosity, "radiosity");
        note(effects.subsurface, "subsurface");
        note(effects.jitteredAreaLight, "jittered area light");
        const std::string inexact = signature.inexactEffects.empty() ? "" : signature.inexactEffects.front();
        PlanFrame(setup, signature, effects, inexact);
        lastSetup_ = setup;
        lastSignature_ = std::move(signature);
        haveLast_ = true;
    }
    plan_.store = store_.get();
    if (!plan_.store) plan_.mode = FramePlan::Mode::kIdle;
    plan_.keepReplays = replayPolicy_.Keep();
    // Every stored block was sent to the front end when it was traced, and the front
    // end's image lives as long as the animation; but radiosity's pretrace draws its
    // coarse passes into that image every frame, over what the last frame left there.
    plan_.skipStoredBlocks = setup.frontEndKeepsImage && !effects.radiosity;
    // Coherent: stored samples or pixels may be reused (kOpaque only when nothing changed).
    current_.coherent = plan_.mode == FramePlan::Mode::kRecord ||
                        (plan_.mode == FramePlan::Mode::kOpaque && !plan_.everythingDirty);
    bookkeeping_ = std::chrono::steady_clock::now() - start;
}

void FrameCoherence::PlanFrame(const FrameSetup &setup, const SceneSignature &signature,
                               const SceneEffects &effects, const std::string &inexact) {
    FrameChange change;
    if (haveLast_) {
        change = CompareFrames(lastSetup_, lastSignature_, setup, signature, effects.photons);
    } else {
        change.newSequence = true;
        change.fullReason = "first frame";
    }
    if (store_ && store_->BlockCount() != BlockCount(setup)) change.newSequence = true;

    if (!inexact.empty()) {
        // Pixels only. A frame in which nothing changed reuses them when the effects'
        // full renders are reproducible from frame to frame; any other renders in full.
        plan_.mode = FramePlan::Mode::kOpaque;
        policy_.Reset();
        if (!store_ || change.newSequence) NewStore(setup);
        const bool reuse = !change.newSequence && change.NothingChanged() &&
                           StaticFrameReproducible(signature.inexactEffects, setup.renderThreads);
        plan_.everythingDirty = !reuse;
        if (!reuse) {
            current_.fullReason = inexact + " (fc cannot keep it exact)";
            if (!change.fullReason.empty() && change.fullReason != "first frame")
                current_.fullReason += "; " + change.fullReason;
        }
        return;
    }

    if (policy_.Paused()) {
        // Resume when the change from the last frame is local (and any back-off is over):
        // the next frame can then reuse what this one records.
        if (!policy_.ResumeWith(!change.newSequence && change.fullReason.empty())) {
            current_.fullReason = (change.fullReason.empty() ? std::string("recording did not pay off")
                                                             : change.fullReason) + " (recording paused)";
            store_.reset();
            plan_.mode = FramePlan::Mode::kIdle;
            return;
        }
        // Paused frames drop the store: one is left only when the last frame was recorded
        // (a full one paused recording), and this local change follows from it.
        if (!store_) {
            change.newSequence = true;
            change.fullReason = "recording resumed";
        }
    }

    plan_.mode = FramePlan::Mode::kRecord;
    wastedIfFull_ = false;
    if (change.newSequence || !store_) {
        NewStore(setup);
        plan_.everythingDirty = true;
        current_.fullReason = change.fullReason;
        // A new sequence after the first frame is full because something global changed.
        wastedIfFull_ = change.fullReason != "first frame" && change.fullReason != "recording resumed";
        NumberUnits(change, signature.units.size(), true);
    } else if (!change.fullReason.empty()) {
        plan_.everythingDirty = true;
        current_.fullReason = change.fullReason;
        wastedIfFull_ = true;
        NumberUnits(change, signature.units.size(), true);
    } else {
        plan_.everythingDirty = false;
        NumberUnits(change, signature.units.size(), false);
        current_.changedUnits = changedIds_.size();
        changes_ = ChangeIndex(std::move(change.hulls), setup.gridResolution);
        plan_.changes = &changes_;
        translucentChanges_ = ChangeIndex(std::move(change.translucentHulls), setup.gridResolution);
        plan_.translucentChanges = &translucentChanges_;
        blockers_ = std::move(change.blockers);
        plan_.blockers = &blockers_;
        plan_.orderChanged = change.orderChanged;
        current_.changedHulls = changes_.HullCount();
        if (!changes_.Empty() && changes_.Bounds().IsFinite()) plan_.changeStamp = drift_.Begin(changes_.Bounds());
        plan_.drift = &drift_;
    }
}

void FrameCoherence::NumberUnits(const FrameChange &change, std::size_t unitCount, bool afresh) {
    for (std::uint32_t id : changedIds_) changedUnits_[id] = 0;
    changedIds_.clear();
    plan_.changedUnitMask = 0;
    if (afresh) {
        unitIds_.Reset(unitCount);
    } else {
        std::vector<std::uint32_t> released;
        unitIds_.Advance(change.continues, change.vanished, released);
    }
    if (changedUnits_.size() < unitIds_.Limit()) changedUnits_.resize(unitIds_.Limit(), 0);
    for (std::size_t k = 0; !afresh && k < change.vanished.size(); ++k) {
        const std::uint32_t id = unitIds_.Previous(change.vanished[k]);
        if (id == UnitIds::kNone || id >= changedUnits_.size()) continue;
        const bool shadowsKept = k < change.shadowsKept.size() && change.shadowsKept[k];
        const bool facesKept = k < change.facesKept.size() && change.facesKept[k];
        changedUnits_[id] = facesKept     ? FramePlan::kUnitFacesKept
                            : shadowsKept ? FramePlan::kUnitRecoloured
                                          : FramePlan::kUnitChanged;
        changedIds_.push_back(id);
        plan_.changedUnitMask |= UnitMaskBit(id);
    }
    // Parts beside a part of their CSG that changed shape: the shadow tests they stopped as
    // opaque blockers meet the hulls (FramePlan::kUnitSiblingChanged).
    for (std::size_t k = 0; !afresh && k < change.partsBesideAChange.size(); ++k) {
        const std::uint32_t index = change.partsBesideAChange[k];
        if (index >= unitIds_.Current().size()) continue;
        const std::uint32_t id = unitIds_.Current()[index];
        if (id >= changedUnits_.size() || changedUnits_[id] != FramePlan::kUnitKept) continue;
        changedUnits_[id] = FramePlan::kUnitSiblingChanged;
        changedIds_.push_back(id);
        plan_.changedUnitMask |= UnitMaskBit(id);
    }
    plan_.unitIds = unitIds_.Current().data();
    plan_.unitCount = unitIds_.Current().size();
    plan_.changedUnits = &changedUnits_;
}

void FrameCoherence::EndFrame(std::uint64_t raysTraced) {
    const auto start = std::chrono::steady_clock::now();
    current_.rays = raysTraced;
    const bool active = plan_.mode != FramePlan::Mode::kIdle;
    if (!active) {
        // fc off or idle: POV-Ray traced every pixel.
        current_.traced = current_.pixels;
    } else {
        current_.traced = counters_.tracedPixels.load();
        current_.reused = counters_.reusedPixels.load();
        current_.samplesTraced = counters_.tracedSamples.load();
        current_.samplesReused = counters_.reusedSamples.load();
        current_.samplesTested = counters_.testedSamples.load();
        current_.samplesCleared = counters_.clearedSamples.load();
        current_.tiedSamplesReplayed = counters_.tiedSamplesReplayed.load();
        current_.tiedSamplesKept = counters_.tiedSamplesKept.load();
        current_.replaySamplesTried = counters_.replaySamplesTried.load();
        current_.shadowSamplesKept = counters_.shadowSamplesKept.load();
        current_.surfaceSamplesKept = counters_.surfaceSamplesKept.load();
        replayPolicy_.AfterFrame(counters_.replayRuns.load(), counters_.replayKeptSegments.load());
        // Blocks this frame did not render missed its changes.
        if (store_) store_->ForgetUntouched();
        current_.storeBytes = store_ ? store_->MemoryBytes() : 0;
        current_.overBudgetBlocks = counters_.overBudgetBlocks.load();
        // A sequence's first frame (or the one recording resumed with) says nothing about
        // whether recording pays: counting it as a good frame reset the busy back-off, so
        // the back-off never grew.
        const bool coherent = !plan_.everythingDirty;
        if (plan_.mode == FramePlan::Mode::kRecord && !coherent) fullFrameRays_ = double(raysTraced);
        if (plan_.mode == FramePlan::Mode::kRecord && (coherent || wastedIfFull_)) {
            // Blocks the memory budget left out are traced whether fc records or not: only
            // the others say whether recording pays (and the rays, all blocks', do not).
            const double unrecorded = double(counters_.unrecordedSamples.load());
            const double taken = double(current_.samplesTraced + current_.samplesReused) - unrecorded;
            const double samplesShare = coherent && taken > 0 ? (double(current_.samplesTraced) - unrecorded) / taken : 0.0;
            const double fullRays = current_.overBudgetBlocks > 0 ? 0.0 : fullFrameRays_;
            policy_.AfterRecordedFrame(wastedIfFull_,
                                       coherent ? RecordingPolicy::WorkShare(samplesShare, double(raysTraced), fullRays) : 0.0);
        }
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
        if (!active)
            for (int y = maskArea_[1]; y <= maskArea_[3]; ++y)
                for (int x = maskArea_[0]; x <= maskArea_[2]; ++x) tracedMask_.Set(x, y);
        char name[32];
        std::snprintf(name, sizeof name, "/retraced%04d.png", current_.frame);
        if (!WriteRetraceMask(maskDir_ + name, tracedMask_, error))
            std::fprintf(stderr, "Frame_Coherence_Mask: cannot write %s\n", error.c_str());
    }
    last_ = current_;
}

}  // namespace povrayfc
