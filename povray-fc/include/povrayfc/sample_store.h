// SampleStore: what frame coherence keeps of a frame, block by block: every camera sample
// a block traced (its position, colour and ray segments) and the block's final pixels.
//
// Why samples, not pixels. POV-Ray's anti-aliasing makes a pixel out of several camera
// samples, and with AA method 1 whether a pixel is supersampled depends on its
// neighbours' samples, so "re-trace the dirty pixels" is not exact at pixel level (the
// last design re-traced whole blocks). Keeping samples instead, a dirty block replays
// POV-Ray's own sampling code unchanged and only the samples whose rays met a change
// are traced again; every other sample returns its stored colour. The same arithmetic on
// the same sample values gives the same pixels, bit for bit, for every AA method.
//
// Why blocks. POV-Ray hands each render block to one thread, so a block's record is
// read and rebuilt by that thread alone, with no locks. A block replayed with the same
// samples as before is updated in place (BlockTracer::End): a traced sample's packed
// segments overwrite its old ones when they take no more bytes, else go to the end of the
// record, the old ones left dead; a record more than a quarter dead is compacted.
// Otherwise the record is replaced whole.
#ifndef POVRAYFC_SAMPLE_STORE_H
#define POVRAYFC_SAMPLE_STORE_H

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "povrayfc/group_index.h"
#include "povrayfc/segment.h"
#include "povrayfc/segment_fans.h"
#include "povrayfc/segment_packing.h"
#include "povrayfc/shadow_replay.h"
#include "povrayfc/surface_replay.h"
#include "povrayfc/tie_replay.h"

namespace povrayfc {

// A unit id's bit in a 64-bit mask of ids (BlockRecord::unitMask): a block none of whose
// bits is among the frame's changed units' has no segment that ended on one.
inline std::uint64_t UnitMaskBit(std::uint32_t id) { return std::uint64_t(1) << ((id * 0x9E3779B1u) >> 26); }

struct StoredSample {
    static constexpr std::uint32_t kEverything = 0xffffffffu;  // segmentCount: any change dirties it

    double x = 0, y = 0;  // position in the image, as POV-Ray traced it: the sample's key
    float colour[5] = {0, 0, 0, 0, 0};  // red, green, blue, filter, transmit
    // Where its segments are packed in BlockRecord::packed, and how many there are.
    std::uint32_t firstByte = 0, segmentCount = 0;
    // BlockRecord::GroupOf(x, y), worked out once when the sample is recorded: the test of
    // a block's samples against a frame's changes reads it for every sample. It fills what
    // was padding.
    std::uint32_t group : 28;
    // A search for one of its rays' nearest intersections ended in a tie the order of the
    // scene's objects decided (tie_watch.h): whenever that order may differ, its tied
    // searches, packed after its segments, are run again (tie_replay.h).
    std::uint32_t orderSensitive : 1;
    // It kept shadow tests that passed something letting light through, packed last: where
    // only their pieces meet a change, they are run again (shadow_replay.h).
    std::uint32_t shadowTests : 1;
    // It was kept by running them again: their pieces may name units that changed since
    // (their ids given to others) and miss those the tests pass now, so every frame in
    // which a unit changes runs them again (shadow_replay.h).
    std::uint32_t shadowStale : 1;
    // It kept surface hits (surface_replay.h), packed after its shadow tests: where only
    // their segments meet a change, they are run again.
    std::uint32_t surfaceHits : 1;
    // Found clean in the frame stamped clearStamp (0: never, or traced since): its segments
    // of the bundle classes in the low BlockHulls::kClassBits bits of `clearance` (every
    // one of its segments in such a class was tested) missed that frame's changes by the
    // float in the other bits beyond their margin (its low mantissa bits cleared: rounded
    // down). While the changes move less than that and reach no other class, the sample
    // stays clean without a test (change_drift.h, block_tracer.cpp).
    std::uint32_t clearStamp = 0;
    std::uint32_t clearance = 0;

    StoredSample() : group(0), orderSensitive(0), shadowTests(0), shadowStale(0), surfaceHits(0) {}
};
static_assert(sizeof(StoredSample) == 56, "StoredSample grew: the store's size per pixel counts it");

struct BlockRecord {
    int left = 0, top = 0, right = -1, bottom = -1;  // inclusive
    // Recorded without segments (an effect fc cannot follow was on): only a frame in
    // which nothing at all changed may reuse it.
    bool opaque = false;
    std::vector<StoredSample> samples;
    // The samples' segments and their bundles (FanApexes numbers), packed
    // (segment_packing.h): each sample's from its firstByte.
    std::vector<std::uint8_t> packed;
    // Bytes of `packed` no sample refers to any more: left by in-place updates until the
    // record is compacted.
    std::size_t deadBytes = 0;
    std::vector<float> pixels;  // 5 floats per pixel, row by row
    FanApexes apexes;           // the camera and light points the segments are bundled by
    // Cones around those bundles, for a quick "nothing near", built when a frame first
    // tests the block (a block no change comes near, or a full frame, never pays).
    BlockFans fans;
    // The same cones per group of kGroupPixels x kGroupPixels pixels (group_fans.h): when
    // a change reaches the block's cones, only the groups it also reaches test their
    // samples' segments one by one. Built and grown with `fans`.
    std::vector<BlockFans> groupFans;
    // Its samples by group, and what each group holds (group_index.h): built whenever
    // `fansBuilt` is set, and cleared with the cones.
    GroupIndex groupIndex;
    bool fansBuilt = false;
    // Segments traced anew and grown into the cones since they were last built: grown
    // cones only widen, so once twice as many were added as the record holds, they are
    // built afresh (when next needed). Counting over frames, not per frame, keeps a block that is
    // partly traced again every frame from paying a whole build every frame.
    std::size_t grownSegments = 0;
    // Whether the cones may grow by `fresh` more segments of a record that holds `live`.
    bool ConesMayGrowBy(std::size_t fresh, std::size_t live) const {
        return fansBuilt && grownSegments + fresh <= 2 * live;
    }
    bool hasEverything = false; // a sample depends on everything (any change dirties it)
    bool hasOrderSensitive = false;  // a sample is StoredSample::orderSensitive
    bool hasStaleShadowTests = false;  // a sample is StoredSample::shadowStale (or was)
    // UnitMaskBit of every unit a segment of the record ended on (a superset once samples
    // are traced again in place: bits are never taken out).
    std::uint64_t unitMask = 0;

    static constexpr int kGroupPixels = 8;

    int Width() const { return right - left + 1; }
    int Height() const { return bottom - top + 1; }
    int GroupsPerRow() const { return (Width() + kGroupPixels - 1) / kGroupPixels; }
    std::size_t GroupCount() const {
        return std::size_t(GroupsPerRow()) * std::size_t((Height() + kGroupPixels - 1) / kGroupPixels);
    }
    // The pixel a sample at (x, y) belongs to, from the block's top left: the nearest pixel
    // centre inside the block (AA method 1 samples the row above and the column left of a
    // block; those count for the block's edge pixels).
    void PixelOf(double x, double y, int &px, int &py) const {
        px = std::clamp(int(std::floor(x + 0.5)), left, right) - left;
        py = std::clamp(int(std::floor(y + 0.5)), top, bottom) - top;
    }
    std::size_t GroupOfPixel(int px, int py) const {
        return std::size_t(py / kGroupPixels) * std::size_t(GroupsPerRow()) + std::size_t(px / kGroupPixels);
    }
    // The group of a sample at (x, y): that of its pixel.
    std::size_t GroupOf(double x, double y) const {
        int px, py;
        PixelOf(x, y, px, py);
        return GroupOfPixel(px, py);
    }
    bool Covers(int l, int t, int r, int b) const { return l == left && t == top && r == right && b == bottom; }
    const float *Pixel(int x, int y) const {
        return &pixels[(std::size_t(y - top) * std::size_t(Width()) + std::size_t(x - left)) * 5];
    }
    // The bytes of `packed` sample `s` holds from its firstByte: its segments, then when it
    // is order-sensitive its tied searches (tie_replay.h), then when it kept any its shadow
    // tests (shadow_replay.h), then its surface hits (surface_replay.h).
    std::size_t SampleBytes(const StoredSample &s) const {
        if (s.segmentCount == StoredSample::kEverything) return 0;
        const std::uint8_t *hits = SurfaceHitsOf(s);
        return std::size_t(hits - (packed.data() + s.firstByte)) + (s.surfaceHits ? SurfaceHitsBytes(hits) : 0);
    }
    // An order-sensitive sample's tied searches (tie_replay.h).
    const std::uint8_t *TiedSearchesOf(const StoredSample &s) const {
        const std::uint8_t *first = packed.data() + s.firstByte;
        return first + PackedSize(first, s.segmentCount);
    }
    // Where a sample's shadow tests are (shadow_replay.h): after its tied searches.
    const std::uint8_t *ShadowTestsOf(const StoredSample &s) const {
        const std::uint8_t *ties = TiedSearchesOf(s);
        return s.orderSensitive ? ties + TiedSearchesBytes(ties) : ties;
    }
    // Where a sample's surface hits are (surface_replay.h): after its shadow tests.
    const std::uint8_t *SurfaceHitsOf(const StoredSample &s) const {
        const std::uint8_t *tests = ShadowTestsOf(s);
        return s.shadowTests ? tests + ShadowTestsBytes(tests) : tests;
    }
    // Unpacks sample `s`'s segments into `segments` and their bundles into `fanOf` (room
    // for s.segmentCount each: UnpackScratch), and, when given, each one's offset in
    // `packed` into `headers`. False when they cannot be read back (segment_packing.h):
    // the sample must count as dirty.
    bool Unpack(const StoredSample &s, Segment *segments, std::uint8_t *fanOf,
                std::uint32_t *headers = nullptr) const {
        const bool ok = UnpackSample(packed.data() + s.firstByte, s.segmentCount, apexes, segments, fanOf, headers);
        if (ok && headers)
            for (std::uint32_t i = 0; i < s.segmentCount; ++i) headers[i] += s.firstByte;
        return ok;
    }
    // As Unpack; a sample whose segments cannot be read back is made to depend on
    // everything (its bytes left dead), and gives none.
    bool UnpackOrForget(StoredSample &s, Segment *segments, std::uint8_t *fanOf) {
        if (Unpack(s, segments, fanOf)) return true;
        deadBytes += PackedSize(packed.data() + s.firstByte, s.segmentCount);
        s.segmentCount = StoredSample::kEverything;
        hasEverything = true;
        return false;
    }
    std::size_t MemoryBytes() const {
        return sizeof(*this) + samples.capacity() * sizeof(StoredSample) + packed.capacity() +
               pixels.capacity() * sizeof(float) + fans.MemoryBytes() + GroupFansMemoryBytes() +
               groupIndex.MemoryBytes();
    }
    std::size_t GroupFansMemoryBytes() const {
        std::size_t bytes = groupFans.capacity() * sizeof(BlockFans);
        for (const BlockFans &g : groupFans) bytes += g.MemoryBytes();
        return bytes;
    }
};

// One slot per render block, by POV-Ray's block serial number. A slot is touched by one
// thread at a time (the one rendering that block); Reset and the statistics run between
// frames.
//
// The store keeps within a memory budget: a block whose record would take it past the
// budget is not kept (Keep says so), and is traced in full whenever it is rendered, until
// records elsewhere shrink or go. What blocks fit depends on the order threads finish
// them in; what a frame shows never does.
class SampleStore {
  public:
    static constexpr std::size_t kNoBudget = ~std::size_t(0);

    SampleStore() = default;
    // The budget covers the whole store, its table of blocks as well as the records.
    explicit SampleStore(std::size_t blocks, std::size_t budgetBytes = kNoBudget)
        : blocks_(blocks), bytes_(blocks, 0), touched_(blocks, 0), leftOut_(blocks, 0), budget_(budgetBytes) {
        total_.store(TableBytes(), std::memory_order_relaxed);
    }

    std::size_t BlockCount() const { return blocks_.size(); }
    // The stored record of block `serial`, or nullptr (never rendered, or out of range).
    // Mutable for the thread rendering that block (it builds the record's cones).
    BlockRecord *Find(std::size_t serial) const { return serial < blocks_.size() ? blocks_[serial].get() : nullptr; }
    // Replaces block `serial`'s record (ignored out of range), or drops it when keeping it
    // would pass the budget; returns whether it was kept.
    bool Put(std::size_t serial, std::unique_ptr<BlockRecord> record) {
        if (serial >= blocks_.size()) return false;
        blocks_[serial] = std::move(record);
        return Keep(serial);
    }
    // Block `serial`'s record changed size in place (traced again, or its cones built):
    // accounts for it, and drops it when it no longer fits the budget. Returns whether it
    // is kept.
    bool Keep(std::size_t serial);
    void Clear() {
        for (std::size_t i = 0; i < blocks_.size(); ++i) Drop(i);
    }
    // Block `serial` has no record because the budget left it out.
    bool LeftOut(std::size_t serial) const { return serial < leftOut_.size() && leftOut_[serial]; }
    // What the store holds now as the budget counts it (MemoryBytes, kept up to date by
    // Put and Keep), and the budget.
    std::size_t AccountedBytes() const { return total_.load(std::memory_order_relaxed); }
    std::size_t BudgetBytes() const { return budget_; }

    // While the store holds less than this, or a 64th of its budget if less, a block that
    // starts recording writes its segments in full (AppendInFull, a third of packing's
    // instructions, three times its bytes); past it, it packs them (PackSegment). So
    // recording pays for packing only where memory counts, and the full form's extra bytes
    // stay under a 32nd of the budget (povray-fc/README.md, "Memory and its budget").
    static constexpr std::size_t kFullSegmentsUpTo = std::size_t(64) << 20;
    bool PackTightly() const { return AccountedBytes() >= std::min(kFullSegmentsUpTo, budget_ / 64); }

    // Block `serial` was rendered (or reused) this frame. From the thread rendering it.
    void Touch(std::size_t serial) {
        if (serial < touched_.size()) touched_[serial] = 1;
    }
    // Forgets every block no thread touched this frame (a renderer told to render only
    // some blocks, e.g. a distributed slave's tiles): its record missed this frame's
    // changes, so it must not be reused later. Between frames.
    void ForgetUntouched() {
        for (std::size_t i = 0; i < blocks_.size(); ++i) {
            if (!touched_[i]) Drop(i);
            touched_[i] = 0;
        }
    }

    std::size_t MemoryBytes() const;
    std::size_t SampleCount() const;
    std::size_t SegmentCount() const;

  private:
    void Drop(std::size_t serial);
    std::size_t TableBytes() const { return sizeof(*this) + blocks_.capacity() * sizeof(blocks_[0]); }

    std::vector<std::unique_ptr<BlockRecord>> blocks_;
    std::vector<std::size_t> bytes_;     // per block: what its record was last counted at
    std::vector<std::uint8_t> touched_;  // per block, this frame
    std::vector<std::uint8_t> leftOut_;  // per block: the budget dropped its record
    std::atomic<std::size_t> total_{0};  // TableBytes() and the sum of bytes_
    std::size_t budget_ = kNoBudget;
};

}  // namespace povrayfc

#endif
