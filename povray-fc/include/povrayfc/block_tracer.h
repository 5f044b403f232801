// BlockTracer: one render thread's side of frame coherence, one render block at a time.
//
// The patched trace task drives it like this for every block POV-Ray hands it:
//
//   if (tracer.Begin(serial, rect))            // nothing in the block changed:
//       send tracer.StoredPixel(x, y) for every pixel, done
//   for every camera sample POV-Ray's sampling code takes at (x, y):
//       if (!tracer.Reuse(x, y, colour)) {      // stored and clean: colour filled in
//           tracer.BeginSample(); trace it; tracer.EndSample(x, y, colour);
//       }
//   tracer.SetPixel(x, y, final colour) for every pixel; tracer.End();
//
// POV-Ray's anti-aliasing code runs unchanged on top (see sample_store.h): a clean
// sample's stored colour is exactly what tracing it again would give.
#ifndef POVRAYFC_BLOCK_TRACER_H
#define POVRAYFC_BLOCK_TRACER_H

#include <cstdint>
#include <memory>
#include <vector>

#include "povrayfc/block_hulls.h"
#include "povrayfc/frame_plan.h"
#include "povrayfc/ray_recording.h"
#include "povrayfc/sample_store.h"
#include "povrayfc/shadow_replay.h"
#include "povrayfc/surface_replay.h"
#include "povrayfc/tie_replay.h"

namespace povrayfc {

class BlockTracer {
  public:
    // Reads the plan of the frame each block is rendered in (the plan must outlive it).
    explicit BlockTracer(const FramePlan &plan) : plan_(&plan) {}
    // Runs tied searches again for this thread (tie_replay.h); without one, an
    // order-sensitive sample is traced again whenever the order of the objects changed.
    void SetTieReplayer(TieReplayer *replayer) { tieReplayer_ = replayer; }
    // Runs shadow tests again for this thread (shadow_replay.h); with one, the samples it
    // records keep their shadow tests that passed something letting light through.
    // `cachesMatter`: the scene lets light through somewhere (SampleRecorder::ShadowCachesMatter).
    void SetShadowReplayer(ShadowReplayer *replayer, bool cachesMatter = true) {
        shadowReplayer_ = replayer;
        recorder_.KeepShadowTests(replayer != nullptr);
        recorder_.ShadowCachesMatter(cachesMatter);
        shadowCachesMatter_ = cachesMatter;
    }
    // Runs surface hits again for this thread (surface_replay.h); with one, a sample traced
    // again because a change reached it keeps its first hits.
    void SetSurfaceReplayer(SurfaceReplayer *replayer) { surfaceReplayer_ = replayer; }

    // Starts block `serial` (POV-Ray's block number) covering [left..right]x[top..bottom].
    // Returns true when the stored block can be sent as it is: then StoredPixel() gives
    // every pixel and no other call is needed for this block.
    bool Begin(std::uint32_t serial, int left, int top, int right, int bottom);
    void StoredPixel(int x, int y, float rgbft[5]) const;
    // After Begin() returned true: the front end already holds this block's pixels.
    bool StoredBlockIsShown() const { return plan_->skipStoredBlocks; }

    // The stored colour of the clean sample at exactly (x, y), kept for this frame too.
    // False when there is none: the caller traces the sample.
    bool Reuse(double x, double y, float rgbft[5]);
    // Records the rays traced until EndSample into the sample at (x, y).
    void BeginSample();
    void EndSample(double x, double y, const float rgbft[5]);

    // The block's final pixel colours, then End() stores the block.
    void SetPixel(int x, int y, const float rgbft[5]);
    void End();
    // After End(): the part of the block the front end must be sent, when it keeps its
    // image (StoredBlockIsShown): the box around the pixels whose colour changed, or the
    // whole block when there was nothing to compare with. False: nothing to send.
    bool ChangedRect(int &left, int &top, int &right, int &bottom) const;
    // After End(): the block was under frame coherence and the front end keeps its image, so
    // it needs only the pixels ChangedRect and PixelChanged report (End() ends Active()).
    bool SendOnlyChanged() const { return endedActive_ && plan_->skipStoredBlocks; }
    // After End(), with ChangedRect: how many pixels changed colour, and whether (x, y) did.
    // Where they are few and scattered, sending them one by one costs less than their
    // rectangle (a reflection and a shadow of a moving object change pixels far apart).
    std::size_t ChangedCount() const { return changedCount_; }
    bool PixelChanged(int x, int y) const {
        return changedPixels_[std::size_t(y - next_.top) * std::size_t(next_.Width()) + std::size_t(x - next_.left)] != 0;
    }

    // The current block is under frame coherence (false: fc is idle this frame, and the
    // caller traces as POV-Ray always does).
    bool Active() const { return active_; }

  private:
    bool FindOld(double x, double y, std::uint32_t &index);
    void IndexOldSamples();
    // The new record's packed segments in its samples' order, each copied once: a reused
    // sample's from old_, a traced one's from next_; fills tracedSegments_ and
    // tracedGroups_. Returns how many segments the record holds.
    std::size_t GatherSegments(BlockRecord &record);
    // When no sample was kept from an old record: the traced samples' segments, copied
    // as they were packed, and their units' mask as they were recorded. Returns how many
    // segments the record holds.
    std::size_t TakeTracedSegments(BlockRecord &record);
    // When the block was replayed with old_'s samples in old_'s order: writes the traced
    // samples, their segments and the pixels into old_ itself (fills tracedSegments_ and
    // tracedGroups_) and returns true. A replayed block traces a few of
    // its samples (on Newton 5%); copying the whole record for them was most of End.
    bool UpdateInPlace();
    // Rewrites `record`'s live packed segments in its samples' order, dropping the dead bytes.
    static void CompactSegments(BlockRecord &record);

    const FramePlan *plan_;
    TieReplayer *tieReplayer_ = nullptr;
    ShadowReplayer *shadowReplayer_ = nullptr;
    SurfaceReplayer *surfaceReplayer_ = nullptr;
    bool shadowCachesMatter_ = true;
    bool active_ = false;   // this block is under fc (mode != kIdle)
    bool endedActive_ = false;  // End() ended a block under fc (SendOnlyChanged)
    bool record_ = false;   // mode kRecord: samples and segments are kept
    bool leftOut_ = false;  // the memory budget left this block's record out (traced in full)
    bool conesPassedBudget_ = false;  // its record went when its cones passed the budget
    bool packTightly_ = true;         // the store holds enough to pack what it records (SampleStore)
    std::uint32_t serial_ = 0;
    BlockRecord *old_ = nullptr;             // the stored record, when it may be reused from
    std::vector<std::uint8_t> oldDirty_;     // per old sample
    // More than seven eighths of old_'s samples are dirty: the change covers the block, and
    // its samples traced again keep no hits (describing them would cost every one of them).
    bool mostlyDirty_ = false;
    std::vector<std::uint32_t> oldIndex_;    // open addressing: old sample index + 1, 0 = empty
    std::uint32_t oldMask_ = 0;
    bool oldIndexed_ = false;                // oldIndex_ holds old_'s samples
    std::uint32_t nextOld_ = 0;              // the old sample after the last one found
    bool sameOrder_ = false;                 // every sample so far is old_'s at its position
    BlockRecord next_;                       // the record being built for this frame (packed segments)
    // The segments traced into next_, as unpacking gives them, and their fans: the cones
    // grow by these.
    std::vector<Segment> nextSegments_;
    std::vector<std::uint8_t> nextFanOf_;
    // UnitMaskBit of every unit a segment traced into next_ ended on, worked out as each
    // sample ends: the new or updated record's mask takes it (a kept sample's comes from
    // its packed bytes).
    std::uint64_t nextUnitMask_ = 0;
    std::vector<std::uint32_t> nextFirstSegment_;  // per sample of next_: its first in nextSegments_ (traced ones)
    std::vector<std::uint8_t> keptFromOld_;  // per sample of next_: reused (its segments are old_'s)
    std::vector<std::size_t> packedSizes_;   // GatherSegments: per sample, its packed bytes
    std::vector<std::pair<std::size_t, std::size_t>> tracedSegments_;  // (first, count) per traced sample, in nextSegments_
    std::vector<std::uint32_t> tracedGroups_;  // per traced sample: its group (BlockRecord::GroupOf)
    std::vector<BlockHulls> groupReach_;       // per group of old_: the changes it may reach
    std::vector<std::uint8_t> groupReaches_;   // per group of old_: groupReach_[g].Any()
    std::vector<std::uint32_t> groupClasses_;  // per group of old_: groupReach_[g].ReachedClasses()
    std::vector<std::uint8_t> tracedPixels_; // per pixel of the block
    std::uint64_t tracedSamples_ = 0, reusedSamples_ = 0;
    int changed_[4] = {0, 0, -1, -1};       // left, top, right, bottom of the changed pixels
    std::vector<std::uint8_t> changedPixels_;   // per pixel of the block: its colour changed
    std::size_t changedCount_ = 0;
    SampleRecorder recorder_;
};

}  // namespace povrayfc

#endif
