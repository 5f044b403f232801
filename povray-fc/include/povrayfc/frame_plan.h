// FramePlan: what the render threads are to do with stored samples in this frame, decided
// by the session before tracing starts and read-only while it runs.
#ifndef POVRAYFC_FRAME_PLAN_H
#define POVRAYFC_FRAME_PLAN_H

#include <atomic>
#include <cstdint>
#include <vector>

#include "povrayfc/change_drift.h"
#include "povrayfc/change_index.h"
#include "povrayfc/dirty_mask.h"
#include "povrayfc/sample_store.h"
#include "povrayfc/shadow_blockers.h"

namespace povrayfc {

// Per-frame counts, added to by the render threads once per block.
struct FrameCounters {
    std::atomic<std::uint64_t> tracedPixels{0}, reusedPixels{0};
    std::atomic<std::uint64_t> tracedSamples{0}, reusedSamples{0};
    std::atomic<std::uint64_t> reusedBlocks{0}, replayedBlocks{0};
    // Samples a change's cones reached: tested segment by segment, or found clean by the
    // clearance they kept from an earlier frame (change_drift.h).
    std::atomic<std::uint64_t> testedSamples{0}, clearedSamples{0};
    // Blocks whose record the memory budget left out: traced in full when next rendered;
    // and the samples traced in blocks it had left out.
    std::atomic<std::uint64_t> overBudgetBlocks{0}, unrecordedSamples{0};
    // Order-sensitive samples clean but for the order of the objects (their tied searches
    // are run again where they could be kept: tie_replay.h), and those kept.
    std::atomic<std::uint64_t> tiedSamplesReplayed{0}, tiedSamplesKept{0};
    // Samples dirty with surface hits or shadow tests kept (surface_replay.h,
    // shadow_replay.h), and those of them kept when the rest of the sample was clean and
    // what they kept, run again, gave what it gave: by their shadow tests (with or without
    // hits), and by their surface hits alone.
    std::atomic<std::uint64_t> replaySamplesTried{0}, shadowSamplesKept{0}, surfaceSamplesKept{0};
    // What trying them cost and saved, in rays: searches and shadow tests run again, and
    // the segments of the samples they kept (ReplayPolicy).
    std::atomic<std::uint64_t> replayRuns{0}, replayKeptSegments{0};

    void Reset() {
        tracedPixels = reusedPixels = tracedSamples = reusedSamples = reusedBlocks = replayedBlocks = 0;
        testedSamples = clearedSamples = overBudgetBlocks = unrecordedSamples = 0;
        tiedSamplesReplayed = tiedSamplesKept = 0;
        replaySamplesTried = shadowSamplesKept = surfaceSamplesKept = 0;
        replayRuns = replayKeptSegments = 0;
    }
};

struct FramePlan {
    enum class Mode {
        kIdle,    // fc off or paused: the hooks do nothing, POV-Ray renders as it always does
        kRecord,  // reuse clean samples, trace and record the others
        kOpaque,  // an effect fc cannot follow: keep the pixels only; reuse them only when
                  // nothing changed and that effect's renders are reproducible
    };
    Mode mode = Mode::kIdle;
    bool everythingDirty = true;       // no stored sample may be reused this frame
    const ChangeIndex *changes = nullptr;  // what changed; empty when nothing did
    // This frame's unit ids (unit_ids.h), by the index the parser wrote into the objects.
    const std::uint32_t *unitIds = nullptr;
    std::size_t unitCount = 0;
    // By unit id: whether the unit changed or vanished this frame, so that a segment that
    // ended on it is dirty; and the UnitMaskBit of every such id.
    static constexpr std::uint8_t kUnitKept = 0;
    static constexpr std::uint8_t kUnitRecoloured = 1;  // same shape, still opaque: shadow
                                                        // tests its surfaces darkened hold
    static constexpr std::uint8_t kUnitChanged = 2;
    // A part of a merge, intersection or difference that stayed while another part of its
    // CSG changed shape: whether its surface is there hangs on that part, so a shadow test
    // it stopped as an opaque blocker holds only while it meets none of the frame's hulls;
    // what ended on it otherwise is tested against the hulls as usual.
    static constexpr std::uint8_t kUnitSiblingChanged = 3;
    // A box that only grew or moved (FrameChange::facesKept): a ray that ended on it meets
    // the new box where it met the old one unless it meets the hulls, which hold where the
    // two differ; a shadow test it stopped as an opaque blocker holds while a blocker of the
    // frame crosses it, as for a changed unit.
    static constexpr std::uint8_t kUnitFacesKept = 4;
    const std::vector<std::uint8_t> *changedUnits = nullptr;
    std::uint64_t changedUnitMask = 0;
    // The opaque balls among this frame's new shapes: a shadow test a changed unit's opaque
    // surface darkened holds while one of them crosses its way (shadow_blockers.h).
    const std::vector<Blocker> *blockers = nullptr;
    // The changed hulls of units a shadow test may pass (FrameChange::translucentHulls):
    // a test an opaque blocker answered is dirty where it meets one. Null or empty: none.
    const ChangeIndex *translucentChanges = nullptr;
    // The ordered list of the scene's objects differs from the last frame's (something
    // changed, appeared, vanished or moved in it): the bounding tree may have another
    // shape, so an order-sensitive sample is kept only when its tied searches, run again,
    // find what they found (tie_watch.h, tie_replay.h).
    bool orderChanged = false;
    // Samples traced again keep their surface hits and every shadow test, to be run again
    // (ReplayPolicy: not while that does not pay).
    bool keepReplays = true;
    // This frame's stamp among the frames whose changes samples keep clearances from (0:
    // none is kept or trusted this frame), and how far the changes moved since each.
    std::uint32_t changeStamp = 0;
    const ChangeDrift *drift = nullptr;
    SampleStore *store = nullptr;
    FrameCounters *counters = nullptr;
    DirtyMask *tracedMask = nullptr;   // pixels traced this frame, when a mask is wanted
    // A block reused whole still holds the same pixels in the front end's image: it is
    // reported done without sending them (no pixel message, no re-encoding).
    bool skipStoredBlocks = false;
};

}  // namespace povrayfc

#endif
