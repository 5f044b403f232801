// Recording of ray segments into the camera sample a render thread is tracing.
//
// POV-Ray's tracing code calls RecordRaySegment() for every ray it traces (camera,
// anti-aliasing, reflected, refracted, continued and shadow rays). When the thread is
// not recording (fc off, or a frame fc renders without recording) the call is one
// thread-local load and a branch, so the hooks stay in the hot path unconditionally.
// When it is, the segment is appended to the sample's list (and packed, segment_packing.h),
// with the id of the unit it ended on: nothing is walked or looked up while tracing (a voxel walk per ray
// used to cost three times the ray itself); the next frame tests the stored segments
// against what changed.
#ifndef POVRAYFC_RAY_RECORDING_H
#define POVRAYFC_RAY_RECORDING_H

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "povrayfc/fan_apexes.h"
#include "povrayfc/scene_signature.h"
#include "povrayfc/segment.h"
#include "povrayfc/segment_packing.h"
#include "povrayfc/shadow_replay.h"
#include "povrayfc/surface_replay.h"
#include "povrayfc/tie_replay.h"

namespace povrayfc {

// The Segment::unit a ray that ended on the parser's unit index `unitIndex` records
// (kUnitNothing: it ended on nothing, Segment::kNoUnit), by this frame's ids `unitIds` of
// `unitCount` units; false when the object has no unit fc knows an id for.
inline bool SegmentUnitOf(std::uint32_t unitIndex, const std::uint32_t *unitIds, std::size_t unitCount,
                          std::uint32_t &unit) {
    if (unitIndex == kUnitNothing) {
        unit = Segment::kNoUnit;
        return true;
    }
    if (unitIndex >= unitCount || unitIds[unitIndex] >= Segment::kOpaqueBlocker) return false;
    unit = unitIds[unitIndex];
    return true;
}

// Collects the segments of one camera sample, appending to a render block's lists (so a
// finished sample needs no copy): each segment and its fan number.
class SampleRecorder {
  public:
    // Starts a sample whose segments are packed onto the end of `packed` (segment_packing.h)
    // and, as unpacking will give them, appended to `segments` (their fans to `fanOf`),
    // against the block's `apexes`. `unitIds[i]` is the id of the frame's unit i
    // (unit_ids.h), for `unitCount` units. `tightly`: pack each segment as it is traced
    // (PackSegment), or write the sample's segments in full when it ends (AppendInFull, in
    // Close).
    void Begin(std::vector<Segment> &segments, std::vector<std::uint8_t> &fanOf, std::vector<std::uint8_t> &packed,
               FanApexes &apexes, const std::uint32_t *unitIds, std::size_t unitCount, bool tightly = true) {
        tightly_ = tightly;
        segments_ = &segments;
        fanOf_ = &fanOf;
        packed_ = &packed;
        apexes_ = &apexes;
        unitIds_ = unitIds;
        unitCount_ = unitCount;
        firstByte_ = packed.size();
        byteStart_.clear();
        first_ = segments.size();
        everything_ = false;
        deep_ = false;
        orderSensitive_ = false;
        ties_.clear();
        tiesComplete_ = true;
        shadowTests_.clear();
        surfaceHits_.clear();
    }
    // Whether the samples keep their shadow tests that passed something letting light
    // through, to run them again (shadow_replay.h): only where they can be run again.
    void KeepShadowTests(bool keep) { keepShadowTests_ = keep; }
    bool KeepsShadowTests() const { return keepShadowTests_; }
    // Whether this sample also keeps its shadow tests that passed nothing: when it keeps its
    // surface hits (KeepSurfaceHits) and its shadow tests can be run again, since they
    // start where its hits end.
    bool KeepsEveryShadowTest() const { return keepSurfaceHits_ && keepShadowTests_; }
    // Whether what the shadow caches held as a test started may change what it gives: in a
    // scene where something lets light through (a cached object is tried first, and what
    // it filtered counts first). Elsewhere only an opaque surface is cached, and a cached
    // one that does not block leaves the test to the loop (patch 0201's exact cache).
    void ShadowCachesMatter(bool matter) { shadowCachesMatter_ = matter; }
    bool ShadowCachesMatterToTests() const { return shadowCachesMatter_; }
    // One such test of the sample (the first kMaxShadowTests are kept).
    void AddShadowTest(const ShadowTest &test) {
        if (shadowTests_.size() < kMaxShadowTests) shadowTests_.push_back(test);
    }
    bool HasShadowTests() const { return !shadowTests_.empty(); }
    // Packs them after the sample's segments and tied searches: its last bytes.
    void PackShadowTests() { povrayfc::PackShadowTests(shadowTests_, *packed_); }
    // Whether this sample keeps the first kMaxSurfaceHits of its rays' hits, to run them
    // again (surface_replay.h): set for each sample, where they can be run again.
    void KeepSurfaceHits(bool keep) { keepSurfaceHits_ = keep; }
    // The hit of the ray Add recorded last, when Add said it is wanted (its segment is the
    // last one).
    void AddSurfaceHit(SurfaceHit hit) {
        if (surfaceHits_.size() >= kMaxSurfaceHits || Count() == 0) return;
        hit.segment = std::uint32_t(Count() - 1);
        surfaceHits_.push_back(hit);
    }
    // Packs them after the sample's shadow tests (none whose segment a shadow test's
    // opaque blocker dropped since: KeepFirst). Returns whether any were packed.
    bool PackSurfaceHits() {
        std::size_t kept = 0;
        for (const SurfaceHit &hit : surfaceHits_)
            if (hit.segment < Count()) surfaceHits_[kept++] = hit;
        surfaceHits_.resize(kept);
        if (kept == 0) return false;
        povrayfc::PackSurfaceHits(surfaceHits_, *packed_);
        return true;
    }
    // A ray that ended on the frame's unit `unit` (the index the parser wrote into what it
    // hit, or kUnitNothing). Returns whether the sample keeps the ray's hit: then
    // AddSurfaceHit is called with it before anything else is recorded.
    bool Add(const double origin[3], const double direction[3], double tmax, std::uint32_t unit) {
        // A ray that cannot be placed: any change must re-trace it (and it must not become
        // the block's camera apex).
        if (!(std::isfinite(origin[0]) && std::isfinite(origin[1]) && std::isfinite(origin[2]))) {
            everything_ = true;
            return false;
        }
        const std::uint8_t fan = apexes_->OriginFan(origin);
        if (!Store(origin, direction, tmax, UnitId(unit), fan)) return false;
        // POV-Ray records a ray when it found what the ray hits, and lights a point
        // (its shadow tests) before it follows the reflected and refracted rays: shadow
        // rays after a ray that did not start at the camera leave the points such rays
        // hit. (Which bundle a segment joins never changes a pixel, only how tight the
        // cones are.)
        deep_ |= fan == FanApexes::kLoose;
        return keepSurfaceHits_ && surfaceHits_.size() < kMaxSurfaceHits;
    }
    // A shadow ray towards the light point `aim` (reaching it, or stopped short by tmax).
    // `opaqueBlocker`: an opaque surface of `unit` ended the test (kOpaqueBlocker).
    void AddAimed(const double origin[3], const double direction[3], double tmax, const double aim[3],
                  std::uint32_t unit, bool opaqueBlocker = false) {
        // A light point that is no point must not become a bundle's apex.
        if (!(std::isfinite(aim[0]) && std::isfinite(aim[1]) && std::isfinite(aim[2]))) {
            everything_ = true;
            return;
        }
        std::uint32_t id = UnitId(unit);
        if (opaqueBlocker && id != Segment::kNoUnit) id |= Segment::kOpaqueBlocker;
        Store(origin, direction, tmax, id, apexes_->AimFan(aim, deep_));
    }
    // Drops the segments recorded after the sample's first `count` (a shadow test's pieces
    // that its opaque blocker made moot).
    void KeepFirst(std::size_t count) {
        if (count >= Count()) return;
        segments_->resize(first_ + count);
        fanOf_->resize(first_ + count);
        if (!tightly_) return;  // nothing is written before Close
        packed_->resize(byteStart_[count]);
        byteStart_.resize(count);
    }
    void MarkEverything() { everything_ = true; }
    // One of the sample's searches for a nearest intersection ended in a tie that the order
    // of the scene's objects decided (tie_watch.h), and it cannot be run again.
    void MarkOrderSensitive() {
        orderSensitive_ = true;
        tiesComplete_ = false;
    }
    // The same for a search that can be run again (tie_replay.h): `search` found the object
    // the parser gave unit index `unitIndex` (kUnitNothing: none). An object without a hash
    // of its own could not be told from another part of its unit.
    void AddTiedSearch(TiedSearch search, std::uint32_t unitIndex) {
        orderSensitive_ = true;
        if (!tiesComplete_) return;
        const bool known = SegmentUnitOf(unitIndex, unitIds_, unitCount_, search.unit) &&
                           (search.unit == Segment::kNoUnit || search.objectHash != 0);
        if (!known || ties_.size() >= kMaxTiedSearches) {
            tiesComplete_ = false;
            return;
        }
        ties_.push_back(search);
    }
    // Packs the order-sensitive sample's tied searches after its segments: the sample's
    // last bytes (BlockRecord::SampleBytes).
    void PackTies() { PackTiedSearches(ties_, tiesComplete_, *packed_); }
    // Ends a sample that keeps its segments: those written in full go onto the bytes now,
    // before its tied searches (PackTies).
    void Close() {
        if (!tightly_) AppendInFull(segments_->data() + first_, fanOf_->data() + first_, Count(), *packed_);
    }

    bool Everything() const { return everything_; }
    bool OrderSensitive() const { return orderSensitive_; }
    std::size_t First() const { return first_; }
    std::size_t Count() const { return segments_->size() - first_; }
    // Drops the sample's segments (it depends on everything anyway).
    void Discard() {
        segments_->resize(first_);
        fanOf_->resize(first_);
        packed_->resize(firstByte_);
        byteStart_.clear();
    }
    // Where the sample's packed segments begin.
    std::size_t FirstByte() const { return firstByte_; }

  private:
    // Appends the segment as unpacking will give it (and packs it, tightly); false when the
    // ray cannot be stored, which makes the sample depend on everything.
    bool Store(const double origin[3], const double direction[3], double tmax, std::uint32_t unit,
               std::uint8_t fan) {
        Segment s;
        bool stored;
        if (tightly_) {
            const std::size_t at = packed_->size();
            stored = PackSegment(origin, direction, tmax, unit, fan, segments_->data() + first_, Count(), *apexes_,
                                 *packed_, s);
            if (stored) byteStart_.push_back(std::uint32_t(at));
        } else {
            stored = MakeSegment(origin, direction, tmax, s);
            s.unit = unit;
        }
        if (!stored) {
            everything_ = true;
            return false;
        }
        segments_->push_back(s);
        fanOf_->push_back(fan);
        return true;
    }
    // The id a segment that ended on the frame's unit `unit` records. An object the parser
    // gave no unit makes the sample depend on everything.
    std::uint32_t UnitId(std::uint32_t unit) {
        std::uint32_t id;
        if (SegmentUnitOf(unit, unitIds_, unitCount_, id)) return id;
        everything_ = true;
        return Segment::kNoUnit;
    }

    std::vector<Segment> *segments_ = nullptr;
    std::vector<std::uint8_t> *fanOf_ = nullptr;
    FanApexes *apexes_ = nullptr;
    const std::uint32_t *unitIds_ = nullptr;
    std::size_t unitCount_ = 0;
    std::vector<std::uint8_t> *packed_ = nullptr;
    std::vector<std::uint32_t> byteStart_;  // per segment of the sample: where it is packed (tightly)
    std::size_t firstByte_ = 0;
    std::size_t first_ = 0;
    bool tightly_ = true;
    bool everything_ = false;
    bool deep_ = false;  // a reflected or refracted ray was recorded in this sample
    bool orderSensitive_ = false;
    std::vector<TiedSearch> ties_;  // the sample's tied searches, in the order they ran
    bool tiesComplete_ = true;      // every tied search of the sample is in ties_
    bool keepShadowTests_ = false;
    bool shadowCachesMatter_ = true;
    std::vector<ShadowTest> shadowTests_;  // the sample's, in the order they ran
    bool keepSurfaceHits_ = false;
    std::vector<SurfaceHit> surfaceHits_;  // the sample's, in the order they ran
};

namespace detail {
extern thread_local SampleRecorder *tlsRecorder;
// While a kept shadow test is run again (the thread records nothing then): where its
// ShadowSegmentRecord writes what answered it.
extern thread_local ShadowRun *tlsShadowRun;
}  // namespace detail

// Adds the segment origin + t*direction, t in [0, tmax], to the sample being recorded on
// this thread. tmax may be huge or infinite (a ray that hit nothing); `unit` is the index
// the parser wrote into the object the ray ended on, or kUnitNothing. Returns whether the
// sample keeps the ray's hit (surface_replay.h): then the patch layer describes it to
// RecordSurfaceHit at once.
inline bool RecordRaySegment(const double origin[3], const double direction[3], double tmax, std::uint32_t unit) {
    return detail::tlsRecorder && detail::tlsRecorder->Add(origin, direction, tmax, unit);
}

inline void RecordSurfaceHit(const SurfaceHit &hit) {
    if (detail::tlsRecorder) detail::tlsRecorder->AddSurfaceHit(hit);
}

// A shadow test's segments, in pieces: up to each transparent object the test passes
// (PassedAt, which shaped the light's colour there), and the last one to the light or to
// the blocker that answered (BlockedAt), recorded when the test returns. POV-Ray's shadow
// loop moves its ray's origin past each transparent object and shortens the remaining
// depth by as much: this reads both where they live.
//
// An opaque blocker (OPAQUE_FLAG) darkens the light exactly, whatever opaque lies before
// or beyond it: the test ends in one kOpaqueBlocker segment, from the loop's last origin
// over the whole depth the test looked up to. It holds for as long as that unit, or
// another opaque solid, still crosses it (shadow_blockers.h), and is tested only against
// the hulls of what a shadow test may pass (FramePlan::translucentChanges): the loop goes
// on past such a surface from a new origin, and whether the ray from there meets the
// blocker is decided in floating point, near an edge either way. For the same reason the
// pieces up to the transparent objects the test passed stay (each ends on its object); a
// test that passed none keeps its one segment alone.
//
// A test that passed something and started with empty shadow caches is also kept whole, to
// be run again (LightColour, CacheHeld, Describe; shadow_replay.h); in a sample traced
// again (SampleRecorder::KeepsEveryShadowTest), so is one that passed nothing, and, where
// only opaque surfaces are cached, one an opaque surface answered or that started with a
// cached object. While a kept test is run again, it writes what answered it to
// detail::tlsShadowRun. Costs one thread-local test when the thread is not recording.
class ShadowSegmentRecord {
  public:
    // `origin` and `depth` (the distance to the light) are the shadow loop's own variables.
    ShadowSegmentRecord(const double *origin, const double direction[3], const double &depth)
        : recorder_(detail::tlsRecorder), origin_(origin), depth_(depth) {
        if (!recorder_) return;
        before_ = recorder_->Count();
        for (int i = 0; i < 3; ++i) {
            direction_[i] = direction[i];
            aim_[i] = origin[i] + depth * direction[i];
        }
    }
    ~ShadowSegmentRecord() {
        if (!recorder_) {
            // A test run again (shadow_replay.h): what answered it.
            if (detail::tlsShadowRun && blocked_ && opaque_) detail::tlsShadowRun->blocker = blocker_;
            return;
        }
        if (!blocked_ || !opaque_ || blocker_ == kUnitNothing) {
            recorder_->AddAimed(origin_, direction_, blocked_ ? blockedAt_ : depth_, aim_, blocker_);
        } else {
            if (!passed_ && recorder_->Count() >= before_) recorder_->KeepFirst(before_);
            recorder_->AddAimed(origin_, direction_, depth_ - projected_, aim_, blocker_, true);
        }
        // Where only opaque surfaces are cached, a test an opaque surface answered is kept too:
        // run again, it must be answered again (its one piece then names what answers it now).
        const bool cachesMatter = recorder_->ShadowCachesMatterToTests();
        if (described_ && !(cacheHeld_ && cachesMatter) && (passed_ || (every_ && (!blocked_ || (opaque_ && !cachesMatter)))))
            KeepTest();
    }
    ShadowSegmentRecord(const ShadowSegmentRecord &) = delete;
    ShadowSegmentRecord &operator=(const ShadowSegmentRecord &) = delete;

    // As the test starts: `colour`, the light's colour the test filters in place (read now,
    // and again when it returns), when the sample keeps its shadow tests (shadow_replay.h).
    void LightColour(const float *colour) {
        if (!recorder_ || !recorder_->KeepsShadowTests()) return;
        colour_ = colour;
        for (int i = 0; i < 3; ++i) test_.colourIn[i] = colour[i];
        if (!recorder_->KeepsEveryShadowTest()) return;
        every_ = true;
        CaptureRay();
    }
    // The shadow caches held an object for the test to try first: it is not kept.
    void CacheHeld(bool held) { cacheHeld_ = held; }
    // Whether Describe is wanted: the test passed something, or its sample keeps every test,
    // and it keeps such tests.
    bool Wanted() const { return (passed_ || every_) && colour_ != nullptr; }
    // As the test ends, when Wanted: what it took besides its ray and the light's colour
    // (the light's index, the ray's flags, the trace level). Without it the test is not kept.
    void Describe(std::uint16_t light, std::uint16_t rayFlags, std::uint8_t traceLevel) {
        test_.light = light;
        test_.rayFlags = rayFlags;
        test_.traceLevel = traceLevel;
        described_ = true;
    }
    // A light with projected_through: the test ignores surfaces within `depth` of the light.
    void ProjectedDepth(double depth) { projected_ = depth; }
    // The test passed a transparent object (the frame's unit `unit`) at `distance` from the
    // current origin; before the loop moves its origin there.
    void PassedAt(double distance, std::uint32_t unit) {
        if (!recorder_) return;
        recorder_->AddAimed(origin_, direction_, distance, aim_, unit);
        // The ray the test started with, before the loop first moves it.
        if (!passed_ && colour_ && !every_) CaptureRay();
        passed_ = true;
    }
    // A blocker (unit `unit`) at `distance` from the current origin answered the test;
    // `opaque`: POV-Ray took the surface there for opaque without looking at its texture
    // (its OPAQUE_FLAG), so the light's share is nothing whatever else the way holds.
    void BlockedAt(double distance, std::uint32_t unit, bool opaque) {
        if (distance < 0.0) return;
        blocked_ = true;
        blockedAt_ = distance;
        blocker_ = unit;
        opaque_ = opaque;
    }

  private:
    SampleRecorder *recorder_;
    const double *origin_;
    const double &depth_;
    double direction_[3] = {0, 0, 0}, aim_[3] = {0, 0, 0};
    std::size_t before_ = 0;  // the sample's segments before this test's
    double projected_ = 0.0;
    bool blocked_ = false;
    double blockedAt_ = 0.0;
    std::uint32_t blocker_ = kUnitNothing;
    bool opaque_ = false;
    bool passed_ = false;  // PassedAt was called: the loop's origin moved
    const float *colour_ = nullptr;  // LightColour was called: the light's colour
    bool every_ = false;             // and the sample keeps every test (the ray is captured)
    bool cacheHeld_ = false;
    bool described_ = false;
    ShadowTest test_;

    void CaptureRay() {
        for (int i = 0; i < 3; ++i) {
            test_.origin[i] = origin_[i];
            test_.direction[i] = direction_[i];
        }
        test_.depth = depth_;
    }
    void KeepTest() {
        const std::size_t count = recorder_->Count();
        if (count < before_ || count - before_ > 0xffff) return;
        test_.firstSegment = std::uint32_t(before_);
        test_.segmentCount = std::uint16_t(count - before_);
        for (int i = 0; i < 3; ++i) test_.colourOut[i] = colour_[i];
        recorder_->AddShadowTest(test_);
    }
};

// Routes this thread's RecordRaySegment() calls into `recorder` until StopRecordingRays().
inline void StartRecordingRays(SampleRecorder &recorder) { detail::tlsRecorder = &recorder; }
inline void StopRecordingRays() { detail::tlsRecorder = nullptr; }

}  // namespace povrayfc

#endif
