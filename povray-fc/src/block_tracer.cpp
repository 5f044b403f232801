// BlockTracer: deciding a block's clean samples, serving them, recording the traced ones.
#include "povrayfc/block_tracer.h"

#include "povrayfc/block_hulls.h"
#include "povrayfc/group_fans.h"
#include "povrayfc/shadow_blockers.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace povrayfc {

namespace {

std::uint64_t Bits(double v) {
    std::uint64_t b;
    std::memcpy(&b, &v, sizeof b);
    return b;
}

std::uint32_t KeyHash(double x, double y) {
    std::uint64_t h = Bits(x) * 0x9E3779B97F4A7C15ull ^ Bits(y);
    h ^= h >> 29;
    h *= 0xBF58476D1CE4E5B9ull;
    return std::uint32_t(h >> 32);
}

// Which of a sample's segments a test passes over: none, or those a mask marks (the pieces
// of the shadow tests a sample kept, when they are run again instead). A type each, so that
// the test every stored sample takes has no mask to look at.
struct SkipNone {
    bool operator()(std::uint32_t) const { return false; }
};
struct SkipMarked {
    const std::uint8_t *marked;
    bool operator()(std::uint32_t i) const { return marked[i] != 0; }
};

// Whether one of the sample's segments may meet a change. When none may, `clearance` says
// how much farther out the box around the changes could have reached with every segment
// tested still missing it (ChangeIndex::UnionClearance; +infinity when no segment's bundle
// reached a change, 0 when one passed through the box and missed the hulls themselves),
// and `untested` the bundle classes (BlockHulls::ClassBit) of the segments not tested.
// Segments `skip` picks are passed over.
template <class Skip = SkipNone>
bool SampleIsDirty(const StoredSample &s, const BlockRecord &record, const ChangeIndex &changes,
                   const BlockHulls &reach, double &clearance, std::uint32_t &untested, Skip skip = Skip()) {
    clearance = std::numeric_limits<double>::infinity();
    untested = 0;
    thread_local UnpackScratch scratch;
    scratch.Fit(s.segmentCount);
    const Segment *segment = scratch.segments.data();
    const std::uint8_t *fanOf = scratch.fans.data();
    if (!record.Unpack(s, scratch.segments.data(), scratch.fans.data())) {
        clearance = 0.0;
        return true;
    }
    for (std::uint32_t i = 0; i < s.segmentCount; ++i) {
        // An opaque blocker's test holds whatever else appears on its way (EndsOnChangedUnit).
        if (!segment[i].HullTested() || skip(i)) continue;
        const BlockHulls::Mask mask = reach.MaskOf(segment[i], fanOf[i]);
        if (mask == 0) {
            untested |= BlockHulls::ClassBit(segment[i], fanOf[i]);
            continue;
        }
        // The union box first (it rejects most segments of a wide fan), measuring by how much.
        const double c = changes.UnionClearance(segment[i]);
        if (c > 0.0) {
            clearance = std::min(clearance, c);
            continue;
        }
        clearance = 0.0;
        if (reach.MayMeetHulls(segment[i], mask, changes)) return true;
    }
    return false;
}

// Whether one of the sample's packed segments ended with a Segment::unit value `matches`
// holds for (kNoUnit skipped), read without unpacking: most samples are ruled out so.
template <class Matches>
bool AnyPackedUnit(const StoredSample &s, const BlockRecord &record, Matches matches) {
    const std::uint8_t *p = record.packed.data() + s.firstByte;
    for (std::uint32_t i = 0; i < s.segmentCount; ++i) {
        std::uint32_t unit;
        p = NextPacked(p, unit);
        if (unit != Segment::kNoUnit && matches(unit)) return true;
    }
    return false;
}

// Whether one of the sample's segments ended on a unit that changed or vanished this frame.
// (FramePlan::changedUnits by id. A shadow test an opaque surface answered holds while
// that unit keeps its shape and stays opaque, or while one of the frame's new opaque
// balls crosses its way: shadow_blockers.h. The test then names that ball's unit, as if
// traced anew: the changed unit's id may go to another unit from the next frame on.)
// Segments `skip` picks are passed over.
template <class Skip = SkipNone>
bool EndsOnChangedUnit(const StoredSample &s, BlockRecord &record, const FramePlan &plan, Skip skip = Skip()) {
    const std::vector<std::uint8_t> &changed = *plan.changedUnits;
    // The units alone first: most samples ended on none that changed.
    if (!AnyPackedUnit(s, record, [&changed](std::uint32_t unit) {
            const std::uint32_t id = unit & ~Segment::kOpaqueBlocker;
            return id < changed.size() && changed[id] != FramePlan::kUnitKept;
        }))
        return false;
    thread_local UnpackScratch scratch;
    scratch.Fit(s.segmentCount);
    const std::vector<std::uint32_t> &headers = scratch.headers;
    if (!record.Unpack(s, scratch.segments.data(), scratch.fans.data(), scratch.headers.data())) return true;
    for (std::uint32_t i = 0; i < s.segmentCount; ++i) {
        const Segment &segment = scratch.segments[i];
        if (segment.unit == Segment::kNoUnit || skip(i)) continue;
        const std::uint32_t unit = segment.UnitId();
        if (unit >= changed.size() || changed[unit] == FramePlan::kUnitKept) continue;
        // A part beside a part of its CSG that changed shape: an opaque blocker's test still
        // holds where the blocking point is in neither that part's old box nor its new one
        // (README.md, "Parts of merges, intersections and differences"); every other segment
        // meets the hulls as usual.
        if (changed[unit] == FramePlan::kUnitSiblingChanged) {
            if ((segment.unit & Segment::kOpaqueBlocker) && (plan.changes == nullptr || plan.changes->MayMeet(segment)))
                return true;
            continue;
        }
        if (!(segment.unit & Segment::kOpaqueBlocker)) {
            // A box that only grew or moved: the hulls, where the two boxes differ, decide.
            if (changed[unit] == FramePlan::kUnitFacesKept) continue;
            return true;
        }
        if (changed[unit] == FramePlan::kUnitRecoloured) continue;
        const Blocker *blocker = plan.blockers ? DarkeningBlocker(segment, *plan.blockers) : nullptr;
        if (blocker == nullptr || blocker->unit >= plan.unitCount) return true;
        const std::uint32_t id = plan.unitIds[blocker->unit];
        if (id >= Segment::kOpaqueBlocker) return true;
        // Too large an id for the width the segment was packed with: traced again.
        if (!RewritePackedUnit(record.packed.data() + headers[i], id | Segment::kOpaqueBlocker)) return true;
        record.unitMask |= UnitMaskBit(id);
        record.groupIndex.unitMask[s.group] |= UnitMaskBit(id);
    }
    return false;
}

// Whether one of the sample's shadow tests an opaque blocker answered may meet a changed
// surface that lets light through (FramePlan::translucentChanges): the loop would go on past
// it from a new origin, and whether it meets the blocker from there is decided in floating
// point (ray_recording.h, ShadowSegmentRecord). Segments `skip` picks are passed over.
template <class Skip = SkipNone>
bool BlockedTestMayMeet(const StoredSample &s, const BlockRecord &record, const ChangeIndex &translucent,
                        Skip skip = Skip()) {
    // The units alone first: most samples have no such test.
    if (!AnyPackedUnit(s, record, [](std::uint32_t unit) { return (unit & Segment::kOpaqueBlocker) != 0; }))
        return false;
    thread_local UnpackScratch scratch;
    scratch.Fit(s.segmentCount);
    if (!record.Unpack(s, scratch.segments.data(), scratch.fans.data())) return true;
    for (std::uint32_t i = 0; i < s.segmentCount; ++i) {
        const Segment &segment = scratch.segments[i];
        if (!segment.HullTested() && !skip(i) && translucent.MayMeet(segment)) return true;
    }
    return false;
}

// Whether sample `s` is clean but for the segments `skip` marks, by the tests above the
// frame asks for (`units`, `blocked`, and `reach`: nullptr when no change reaches its group).
bool CleanBeside(const StoredSample &s, BlockRecord &record, const FramePlan &plan, bool units, bool blocked,
                 const BlockHulls *reach, const std::uint8_t *skip) {
    const SkipMarked pieces{skip};
    if (units && EndsOnChangedUnit(s, record, plan, pieces)) return false;
    if (blocked && BlockedTestMayMeet(s, record, *plan.translucentChanges, pieces)) return false;
    double clearance;
    std::uint32_t untested;
    return !(reach && SampleIsDirty(s, record, *plan.changes, *reach, clearance, untested, pieces));
}

// The surface hits a sample kept, run again through `replayer`: whether each found what it
// found (surface_replay.h), and the ids (this frame's) of the units they hit now.
bool SurfaceHitsHold(const SurfaceHit *hits, std::size_t count, const FramePlan &plan, SurfaceReplayer *replayer,
                     std::uint32_t *units, std::uint64_t &runs) {
    for (std::size_t h = 0; h < count; ++h) {
        std::uint64_t signature;
        std::uint32_t unitIndex;
        ++runs;
        if (!replayer->Replay(hits[h], signature, unitIndex) || signature != hits[h].signature) return false;
        if (!SegmentUnitOf(unitIndex, plan.unitIds, plan.unitCount, units[h])) return false;
    }
    return true;
}

// Names, in the sample's packed segments, the units its kept hits found in this frame
// (their segments are otherwise the new frame's: the same ray to the same depth). False
// when a segment cannot be rewritten (then it must be traced).
bool RenameHitUnits(const StoredSample &s, BlockRecord &record, const SurfaceHit *hits, std::size_t count,
                    const std::uint32_t *units) {
    thread_local UnpackScratch scratch;
    scratch.Fit(s.segmentCount);
    if (!record.Unpack(s, scratch.segments.data(), scratch.fans.data(), scratch.headers.data())) return false;
    for (std::size_t h = 0; h < count; ++h) {
        const Segment &segment = scratch.segments[hits[h].segment];
        // Both nothing: the signature says whether the search found anything.
        if (units[h] == Segment::kNoUnit && segment.unit == Segment::kNoUnit) continue;
        if (units[h] == Segment::kNoUnit || segment.unit == Segment::kNoUnit) return false;
        if (!RewritePackedUnit(record.packed.data() + scratch.headers[hits[h].segment], units[h])) return false;
        record.unitMask |= UnitMaskBit(units[h]);
        record.groupIndex.unitMask[s.group] |= UnitMaskBit(units[h]);
    }
    return true;
}

// Whether `tests`, run again with `runs`, left pieces that are the new frame's: each is one
// piece and passed nothing then and now, and it reached the light both times or an opaque
// surface answered it both times. Then each answered piece is made to name the unit that
// answers it now (its id this frame), and the sample holds the new frame's segments only.
bool TestsAsTraced(const StoredSample &s, BlockRecord &record, const FramePlan &plan, const ShadowTest *tests,
                   const ShadowRun *runs, std::size_t count) {
    for (std::size_t t = 0; t < count; ++t)
        if (tests[t].segmentCount != 1 || runs[t].passed) return false;
    thread_local UnpackScratch scratch;
    scratch.Fit(s.segmentCount);
    if (!record.Unpack(s, scratch.segments.data(), scratch.fans.data(), scratch.headers.data())) return false;
    std::uint32_t ids[kMaxShadowTests];
    for (std::size_t t = 0; t < count; ++t) {
        const std::uint32_t unit = scratch.segments[tests[t].firstSegment].unit;
        if (unit == Segment::kNoUnit) {
            if (runs[t].blocker != kUnitNothing) return false;
            continue;
        }
        if (!(unit & Segment::kOpaqueBlocker) || runs[t].blocker == kUnitNothing) return false;
        if (!SegmentUnitOf(runs[t].blocker, plan.unitIds, plan.unitCount, ids[t]) || ids[t] == Segment::kNoUnit) return false;
    }
    for (std::size_t t = 0; t < count; ++t) {
        if (scratch.segments[tests[t].firstSegment].unit == Segment::kNoUnit) continue;
        if (!RewritePackedUnit(record.packed.data() + scratch.headers[tests[t].firstSegment], ids[t] | Segment::kOpaqueBlocker))
            return false;
        record.unitMask |= UnitMaskBit(ids[t]);
        record.groupIndex.unitMask[s.group] |= UnitMaskBit(ids[t]);
    }
    return true;
}

// How a dirty sample was kept by running what it kept again: by its surface hits alone, or
// with its shadow tests (whose old pieces are then the new frame's, or stale).
enum class KeptBy { kNothing, kSurfaceHits, kShadowTestsAsTraced, kShadowTests };

// Whether a sample found dirty is clean but for the segments of the surface hits and the
// pieces of the shadow tests it kept, and those, run again, give what they gave
// (surface_replay.h, shadow_replay.h). The hits alone are tried first: a sample kept by its
// hits is as good as traced, one kept by its shadow tests is stale. `units`, `blocked` and
// `reach` say which tests the frame asks for, as for any sample.
KeptBy KeptByReplays(const StoredSample &s, BlockRecord &record, const FramePlan &plan, bool units, bool blocked,
                     const BlockHulls *reach, SurfaceReplayer *surfaceReplayer, ShadowReplayer *shadowReplayer,
                     bool shadowCachesMatter, std::uint64_t &runs) {
    if (s.segmentCount == StoredSample::kEverything) return KeptBy::kNothing;
    SurfaceHit hits[kMaxSurfaceHits];
    const std::size_t hitCount =
        s.surfaceHits && surfaceReplayer ? UnpackSurfaceHits(record.SurfaceHitsOf(s), hits) : 0;
    ShadowTest tests[kMaxShadowTests];
    const std::size_t testCount = s.shadowTests && shadowReplayer ? UnpackShadowTests(record.ShadowTestsOf(s), tests) : 0;
    if (hitCount == 0 && testCount == 0) return KeptBy::kNothing;
    thread_local std::vector<std::uint8_t> skip;
    skip.assign(s.segmentCount, 0);
    for (std::size_t h = 0; h < hitCount; ++h) {
        if (hits[h].segment >= s.segmentCount) return KeptBy::kNothing;
        skip[hits[h].segment] = 1;
    }
    std::uint32_t hitUnits[kMaxSurfaceHits];
    // A stale sample runs its shadow tests whenever it is tried (shadow_replay.h).
    if (hitCount > 0 && !s.shadowStale && CleanBeside(s, record, plan, units, blocked, reach, skip.data())) {
        if (!SurfaceHitsHold(hits, hitCount, plan, surfaceReplayer, hitUnits, runs)) return KeptBy::kNothing;
        return RenameHitUnits(s, record, hits, hitCount, hitUnits) ? KeptBy::kSurfaceHits : KeptBy::kNothing;
    }
    if (testCount == 0) return KeptBy::kNothing;
    for (std::size_t t = 0; t < testCount; ++t) {
        if (std::size_t(tests[t].firstSegment) + tests[t].segmentCount > s.segmentCount) return KeptBy::kNothing;
        std::fill_n(skip.begin() + tests[t].firstSegment, tests[t].segmentCount, std::uint8_t(1));
    }
    if (!CleanBeside(s, record, plan, units, blocked, reach, skip.data())) return KeptBy::kNothing;
    if (hitCount > 0 && !SurfaceHitsHold(hits, hitCount, plan, surfaceReplayer, hitUnits, runs)) return KeptBy::kNothing;
    ShadowRun testRuns[kMaxShadowTests];
    runs += testCount;
    if (!ShadowTestsHold(tests, testCount, shadowReplayer, shadowCachesMatter, testRuns)) return KeptBy::kNothing;
    if (hitCount > 0 && !RenameHitUnits(s, record, hits, hitCount, hitUnits)) return KeptBy::kNothing;
    return TestsAsTraced(s, record, plan, tests, testRuns, testCount) ? KeptBy::kShadowTestsAsTraced : KeptBy::kShadowTests;
}

// A clearance (>= 0, rounded down to a float whose low mantissa bits are cleared) and the
// bundle classes it holds for, in one word (StoredSample::clearance).
constexpr std::uint32_t kClassMask = (std::uint32_t(1) << BlockHulls::kClassBits) - 1;

std::uint32_t PackClearance(double clearance, std::uint32_t classes) {
    float f = float(clearance);
    if (double(f) > clearance) f = std::nextafter(f, 0.0f);
    std::uint32_t bits;
    std::memcpy(&bits, &f, sizeof bits);
    return (bits & ~kClassMask) | (classes & kClassMask);  // a positive float only shrinks so
}

float ClearanceOf(std::uint32_t packed) {
    const std::uint32_t bits = packed & ~kClassMask;
    float f;
    std::memcpy(&f, &bits, sizeof f);
    return f;
}

}  // namespace

bool BlockTracer::Begin(std::uint32_t serial, int left, int top, int right, int bottom) {
    const FramePlan &plan = *plan_;
    endedActive_ = false;
    sameOrder_ = false;
    active_ = plan.mode != FramePlan::Mode::kIdle;
    if (!active_) return false;
    record_ = plan.mode == FramePlan::Mode::kRecord;
    serial_ = serial;
    tracedSamples_ = reusedSamples_ = 0;
    conesPassedBudget_ = false;

    next_.left = left;
    next_.top = top;
    next_.right = right;
    next_.bottom = bottom;
    next_.opaque = !record_;
    next_.samples.clear();
    next_.packed.clear();
    next_.apexes.Clear();
    nextUnitMask_ = 0;
    nextSegments_.clear();
    nextFanOf_.clear();
    nextFirstSegment_.clear();
    keptFromOld_.clear();
    const std::size_t area = std::size_t(right - left + 1) * std::size_t(bottom - top + 1);
    next_.pixels.assign(area * 5, 0.0f);
    tracedPixels_.assign(area, 0);

    plan.store->Touch(serial);
    packTightly_ = plan.store->PackTightly();
    old_ = plan.store->Find(serial);
    mostlyDirty_ = false;
    leftOut_ = old_ == nullptr && plan.store->LeftOut(serial);
    if (old_ && (!old_->Covers(left, top, right, bottom) || old_->opaque != !record_)) old_ = nullptr;
    if (old_ && plan.everythingDirty) old_ = nullptr;
    if (!old_) return false;

    // A new order of the scene's objects concerns the order-sensitive samples alone (their
    // tied searches are run again); a changed unit, the samples with a segment that ended
    // on it.
    const bool orderMatters = plan.orderChanged && old_->hasOrderSensitive;
    const bool unitsChanged = plan.changedUnits != nullptr && (old_->unitMask & plan.changedUnitMask) != 0;
    const bool translucentChanged = plan.translucentChanges != nullptr && !plan.translucentChanges->Empty();
    // Samples kept by running their shadow tests again: any changed unit may be one they pass
    // (a glass that vanished leaves no hull, and the block's unit mask need not name it), and
    // a new order may decide a tie on their way that their kept tied searches do not hold.
    const bool staleAsked = old_->hasStaleShadowTests &&
                            ((plan.changedUnits != nullptr && plan.changedUnitMask != 0) || plan.orderChanged);
    const bool nothingChanged =
        (plan.changes == nullptr || plan.changes->Empty()) && !orderMatters && !unitsChanged && !staleAsked;
    if (nothingChanged) {
        plan.counters->reusedPixels += area;
        plan.counters->reusedSamples += old_->samples.size();
        plan.counters->reusedBlocks += 1;
        return true;
    }
    if (!record_) {
        old_ = nullptr;  // an opaque block is reused only when nothing changed
        return false;
    }

    // The block's clean samples: those none of whose rays may meet a change. Most blocks
    // are far from every change, which the cones around their segments show at once.
    const std::size_t n = old_->samples.size();
    if (!old_->fansBuilt) {
        BuildRecordFans(*old_);
        // The cones count against the memory budget too: past it, the record goes (Keep
        // drops it) and the block is traced in full like one never recorded.
        if (!plan.store->Keep(serial)) {
            old_ = nullptr;
            leftOut_ = true;
            conesPassedBudget_ = true;
            return false;
        }
    }
    const BlockHulls reach = FindBlockHulls(old_->fans, *plan.changes);
    bool anyDirty = false;
    // The cones hold no opaque blocker's test: a translucent change walks every group
    // that has one.
    if (reach.Any() || old_->hasEverything || orderMatters || unitsChanged || translucentChanged || staleAsked) {
        // The block's cones reach a change (or a sample depends on everything): narrow
        // it down to the groups of samples whose own cones reach it.
        groupReach_.resize(old_->groupFans.size());
        groupReaches_.resize(old_->groupFans.size());
        for (std::size_t g = 0; g < groupReach_.size(); ++g) {
            groupReach_[g] = FindGroupHulls(old_->groupFans[g], *plan.changes, reach);
            groupReaches_[g] = groupReach_[g].Any();
        }
        groupClasses_.resize(old_->groupFans.size());
        for (std::size_t g = 0; g < groupReach_.size(); ++g) groupClasses_[g] = groupReach_[g].ReachedClasses();
        // Group by group, passing over those nothing of this frame concerns (group_index.h).
        const GroupIndex &index = old_->groupIndex;
        oldDirty_.assign(n, 0);
        std::uint64_t tested = 0, cleared = 0, tiedReplayed = 0, tiedKept = 0, replayTried = 0, shadowKept = 0,
                      surfaceKept = 0, replayRuns = 0, keptSegments = 0, dirtyCount = 0;
        for (std::size_t g = 0; g < groupReach_.size(); ++g) {
            const std::uint8_t flags = index.flags[g];
            const bool everything = (flags & GroupIndex::kEverything) != 0;
            const bool order = orderMatters && (flags & GroupIndex::kOrderSensitive);
            const bool units = unitsChanged && (index.unitMask[g] & plan.changedUnitMask) != 0;
            const bool blocked = translucentChanged && (flags & GroupIndex::kOpaqueBlockerTest);
            const bool stale = staleAsked && (flags & GroupIndex::kStaleShadowTests);
            if (!groupReaches_[g] && !everything && !order && !units && !blocked && !stale) continue;
            for (std::uint32_t k = index.Begin(g); k < index.End(g); ++k) {
                const std::uint32_t i = index.samples[k];
                StoredSample &s = old_->samples[i];
                bool dirty = s.segmentCount == StoredSample::kEverything || (stale && s.shadowStale) ||
                             (units && EndsOnChangedUnit(s, *old_, plan)) ||
                             (blocked && BlockedTestMayMeet(s, *old_, *plan.translucentChanges));
                if (!dirty && groupReaches_[g]) {
                    // Clean by what it kept, while the changes stay near where they were then
                    // and reach no class of its segments it did not test; else tested,
                    // keeping what it finds.
                    if ((groupClasses_[g] & ~s.clearance & kClassMask) == 0 && plan.drift &&
                        plan.drift->Since(s.clearStamp) < ClearanceOf(s.clearance)) {
                        ++cleared;
                    } else {
                        ++tested;
                        double clearance;
                        std::uint32_t untested;
                        dirty = SampleIsDirty(s, *old_, *plan.changes, groupReach_[g], clearance, untested);
                        if (!dirty && plan.changeStamp != 0 && clearance > 0.0) {
                            s.clearStamp = plan.changeStamp;
                            s.clearance = PackClearance(clearance, ~untested);
                        }
                    }
                }
                // Dirty through the surface hits or shadow tests it kept alone, maybe: they
                // are run again.
                if (dirty && ((s.surfaceHits && surfaceReplayer_) || (s.shadowTests && shadowReplayer_))) {
                    ++replayTried;
                    const KeptBy kept = KeptByReplays(s, *old_, plan, units, blocked,
                                                      groupReaches_[g] ? &groupReach_[g] : nullptr, surfaceReplayer_,
                                                      shadowReplayer_, shadowCachesMatter_, replayRuns);
                    dirty = kept == KeptBy::kNothing;
                    if (!dirty) keptSegments += s.segmentCount;
                    if (kept == KeptBy::kSurfaceHits) ++surfaceKept;
                    if (kept == KeptBy::kShadowTestsAsTraced) {
                        ++shadowKept;
                        s.shadowStale = 0;  // every segment it holds is now this frame's
                    }
                    if (kept == KeptBy::kShadowTests) {
                        ++shadowKept;
                        s.shadowStale = 1;
                        old_->hasStaleShadowTests = true;
                        old_->groupIndex.flags[g] |= GroupIndex::kStaleShadowTests;
                    }
                }
                // Clean but for the order of the objects: its tied searches, run again, must
                // find what they found (tie_replay.h).
                if (!dirty && order && s.orderSensitive) {
                    ++tiedReplayed;
                    dirty = !TiedSearchesHold(old_->TiedSearchesOf(s), tieReplayer_, plan.unitIds, plan.unitCount);
                    if (!dirty) ++tiedKept;
                }
                oldDirty_[i] = dirty;
                anyDirty |= dirty;
                dirtyCount += dirty;
            }
        }
        plan.counters->testedSamples += tested;
        plan.counters->clearedSamples += cleared;
        plan.counters->tiedSamplesReplayed += tiedReplayed;
        plan.counters->tiedSamplesKept += tiedKept;
        plan.counters->replaySamplesTried += replayTried;
        plan.counters->shadowSamplesKept += shadowKept;
        plan.counters->surfaceSamplesKept += surfaceKept;
        plan.counters->replayRuns += replayRuns;
        plan.counters->replayKeptSegments += keptSegments;
        mostlyDirty_ = 8 * dirtyCount > 7 * n;
    }
    if (!anyDirty) {
        plan.counters->reusedPixels += area;
        plan.counters->reusedSamples += n;
        plan.counters->reusedBlocks += 1;
        return true;
    }
    nextOld_ = 0;
    oldIndexed_ = false;
    sameOrder_ = true;
    // Reused segments keep their fan numbers, so the new record starts from the old apexes.
    next_.apexes = old_->apexes;
    return false;
}

void BlockTracer::StoredPixel(int x, int y, float rgbft[5]) const {
    const float *c = old_->Pixel(x, y);
    std::copy(c, c + 5, rgbft);
}

void BlockTracer::IndexOldSamples() {
    std::uint32_t size = 16;
    while (size < 2 * old_->samples.size()) size *= 2;
    oldIndex_.assign(size, 0);
    oldMask_ = size - 1;
    for (std::uint32_t i = 0; i < old_->samples.size(); ++i) {
        const StoredSample &s = old_->samples[i];
        std::uint32_t slot = KeyHash(s.x, s.y) & oldMask_;
        while (oldIndex_[slot] != 0) slot = (slot + 1) & oldMask_;
        oldIndex_[slot] = i + 1;
    }
}

bool BlockTracer::FindOld(double x, double y, std::uint32_t &index) {
    // POV-Ray asks for a block's samples in the order it asked for them last frame,
    // unless anti-aliasing now supersamples other pixels: try the one after the last
    // found first, and index them all only when that misses.
    // Exact comparisons: POV-Ray computes a sample's position the same way every frame.
    if (nextOld_ < old_->samples.size()) {
        const StoredSample &s = old_->samples[nextOld_];
        if (s.x == x && s.y == y) {
            index = nextOld_++;
            return true;
        }
    }
    if (!oldIndexed_) {
        IndexOldSamples();
        oldIndexed_ = true;
    }
    std::uint32_t slot = KeyHash(x, y) & oldMask_;
    for (;;) {
        const std::uint32_t entry = oldIndex_[slot];
        if (entry == 0) return false;
        const StoredSample &s = old_->samples[entry - 1];
        if (s.x == x && s.y == y) {
            index = entry - 1;
            nextOld_ = index + 1;
            return true;
        }
        slot = (slot + 1) & oldMask_;
    }
}

bool BlockTracer::Reuse(double x, double y, float rgbft[5]) {
    if (!active_ || !record_ || !old_) return false;
    std::uint32_t i;
    if (!FindOld(x, y, i) || oldDirty_[i]) return false;
    const StoredSample &s = old_->samples[i];
    std::copy(s.colour, s.colour + 5, rgbft);
    sameOrder_ = sameOrder_ && i == next_.samples.size();
    // Its segments stay in old_ until End gathers the new record's (one copy, not two).
    next_.samples.push_back(s);
    keptFromOld_.push_back(1);
    nextFirstSegment_.push_back(0);
    ++reusedSamples_;
    return true;
}

void BlockTracer::BeginSample() {
    if (!active_ || !record_) return;
    recorder_.Begin(nextSegments_, nextFanOf_, next_.packed, next_.apexes, plan_->unitIds, plan_->unitCount,
                    packTightly_);
    // Traced again where a record was: a change reached it, and may reach it again. It keeps
    // its hits, and the shadow tests that light them.
    recorder_.KeepSurfaceHits(surfaceReplayer_ != nullptr && old_ != nullptr && plan_->keepReplays && !mostlyDirty_);
    StartRecordingRays(recorder_);
}

void BlockTracer::EndSample(double x, double y, const float rgbft[5]) {
    if (!active_) return;
    ++tracedSamples_;
    int px, py;
    next_.PixelOf(x, y, px, py);
    tracedPixels_[std::size_t(py) * std::size_t(next_.Width()) + std::size_t(px)] = 1;
    if (!record_) return;
    StopRecordingRays();
    if (old_) {
        const std::size_t at = next_.samples.size();
        sameOrder_ = sameOrder_ && at < old_->samples.size() && old_->samples[at].x == x && old_->samples[at].y == y;
    }
    StoredSample s;
    s.x = x;
    s.y = y;
    s.group = std::uint32_t(next_.GroupOfPixel(px, py));
    s.orderSensitive = recorder_.OrderSensitive();
    std::copy(rgbft, rgbft + 5, s.colour);
    if (recorder_.Everything()) {
        recorder_.Discard();  // its segments say nothing
        s.segmentCount = StoredSample::kEverything;
    } else {
        s.firstByte = std::uint32_t(recorder_.FirstByte());
        s.segmentCount = std::uint32_t(recorder_.Count());
        recorder_.Close();
        if (s.orderSensitive) recorder_.PackTies();
        if (recorder_.HasShadowTests()) {
            s.shadowTests = 1;
            recorder_.PackShadowTests();
        }
        if (recorder_.PackSurfaceHits()) s.surfaceHits = 1;
        for (std::size_t k = recorder_.First(); k < nextSegments_.size(); ++k)
            if (nextSegments_[k].unit != Segment::kNoUnit) nextUnitMask_ |= UnitMaskBit(nextSegments_[k].UnitId());
    }
    next_.samples.push_back(s);
    keptFromOld_.push_back(0);
    nextFirstSegment_.push_back(std::uint32_t(recorder_.First()));
}

void BlockTracer::SetPixel(int x, int y, const float rgbft[5]) {
    if (!active_) return;
    float *c = &next_.pixels[(std::size_t(y - next_.top) * std::size_t(next_.Width()) + std::size_t(x - next_.left)) * 5];
    std::copy(rgbft, rgbft + 5, c);
}

void BlockTracer::End() {
    if (!active_) return;
    const FramePlan &plan = *plan_;
    // A pixel counts as traced when one of its own samples was, or when its colour
    // changed: with anti-aliasing a pixel can change through a neighbour's sample alone
    // (AA method 1 decides to supersample from the neighbours; method 2 shares corners).
    const int w = next_.Width();
    if (old_) {
        changed_[0] = next_.right + 1;
        changed_[1] = next_.bottom + 1;
        changed_[2] = next_.left - 1;
        changed_[3] = next_.top - 1;
        changedPixels_.assign(tracedPixels_.size(), 0);
        changedCount_ = 0;
        for (std::size_t i = 0; i < tracedPixels_.size(); ++i) {
            if (std::memcmp(&old_->pixels[i * 5], &next_.pixels[i * 5], 5 * sizeof(float)) == 0) continue;
            tracedPixels_[i] = 1;
            changedPixels_[i] = 1;
            ++changedCount_;
            const int x = next_.left + int(i % std::size_t(w)), y = next_.top + int(i / std::size_t(w));
            changed_[0] = std::min(changed_[0], x);
            changed_[1] = std::min(changed_[1], y);
            changed_[2] = std::max(changed_[2], x);
            changed_[3] = std::max(changed_[3], y);
        }
    } else {
        changed_[0] = next_.left;
        changed_[1] = next_.top;
        changed_[2] = next_.right;
        changed_[3] = next_.bottom;
        changedPixels_.assign(tracedPixels_.size(), 1);
        changedCount_ = tracedPixels_.size();
    }
    std::uint64_t traced = 0;
    for (std::size_t i = 0; i < tracedPixels_.size(); ++i) {
        if (!tracedPixels_[i]) continue;
        ++traced;
        if (plan.tracedMask)
            plan.tracedMask->Set(next_.left + int(i % std::size_t(w)), next_.top + int(i / std::size_t(w)));
    }
    plan.counters->tracedPixels += traced;
    plan.counters->reusedPixels += tracedPixels_.size() - traced;
    plan.counters->tracedSamples += tracedSamples_;
    if (leftOut_) plan.counters->unrecordedSamples += tracedSamples_;
    plan.counters->reusedSamples += reusedSamples_;
    plan.counters->replayedBlocks += 1;

    if (record_ && old_ && UpdateInPlace()) {
        if (!plan.store->Keep(serial_)) ++plan.counters->overBudgetBlocks;
        old_ = nullptr;
        active_ = false;
        endedActive_ = true;
        return;
    }
    // An exact-size copy: the scratch keeps its capacity for the next block, and the
    // store holds no slack.
    auto record = std::make_unique<BlockRecord>();
    record->left = next_.left;
    record->top = next_.top;
    record->right = next_.right;
    record->bottom = next_.bottom;
    record->opaque = next_.opaque;
    record->samples.assign(next_.samples.begin(), next_.samples.end());
    record->pixels.assign(next_.pixels.begin(), next_.pixels.end());
    if (record_) {
        record->apexes = next_.apexes;
        const std::size_t live = old_ ? GatherSegments(*record) : TakeTracedSegments(*record);
        // Grow the old cones by what was traced anew, until twice what the block holds was
        // grown into them (BlockRecord::grownSegments); otherwise they are built when needed.
        std::size_t fresh = 0;
        for (const auto &range : tracedSegments_) fresh += range.second;
        if (old_ && old_->ConesMayGrowBy(fresh, live)) {
            record->groupFans = std::move(old_->groupFans);  // old_ is replaced below
            GrowRecordFans(*record, nextSegments_.data(), nextFanOf_.data(), tracedSegments_, tracedGroups_);
            BuildGroupIndex(*record, &old_->groupIndex, &keptFromOld_);
            record->grownSegments = old_->grownSegments + fresh;
        }
        for (const StoredSample &s : record->samples) {
            record->hasEverything |= s.segmentCount == StoredSample::kEverything;
            record->hasOrderSensitive |= s.orderSensitive;
            record->hasStaleShadowTests |= s.shadowStale;
        }
    }
    old_ = nullptr;
    if (!plan.store->Put(serial_, std::move(record)) || conesPassedBudget_) ++plan.counters->overBudgetBlocks;
    active_ = false;
    endedActive_ = true;
}

std::size_t BlockTracer::TakeTracedSegments(BlockRecord &record) {
    // Every sample was traced, so next_.packed holds their segments in their order, each
    // sample's from its firstByte (a discarded sample's bytes were cut off again).
    record.packed.assign(next_.packed.begin(), next_.packed.end());
    record.unitMask = nextUnitMask_;
    std::size_t live = 0;
    for (const StoredSample &s : record.samples)
        if (s.segmentCount != StoredSample::kEverything) live += s.segmentCount;
    return live;
}

std::size_t BlockTracer::GatherSegments(BlockRecord &record) {
    std::size_t total = 0, live = 0;
    packedSizes_.assign(record.samples.size(), 0);
    for (std::size_t i = 0; i < record.samples.size(); ++i) {
        const StoredSample &s = record.samples[i];
        if (s.segmentCount == StoredSample::kEverything) continue;
        const BlockRecord &from = keptFromOld_[i] ? *old_ : next_;
        packedSizes_[i] = from.SampleBytes(s);
        total += packedSizes_[i];
        live += s.segmentCount;
    }
    record.packed.reserve(total);
    tracedSegments_.clear();
    tracedGroups_.clear();
    for (std::size_t i = 0; i < record.samples.size(); ++i) {
        StoredSample &s = record.samples[i];
        if (s.segmentCount == StoredSample::kEverything) continue;
        const std::size_t at = record.packed.size();
        // Reused segments keep their fan numbers: the new record starts from the old apexes,
        // and a record is reused from only once its fans are built (its numbers valid).
        const bool kept = keptFromOld_[i] != 0;
        const std::uint8_t *first = (kept ? *old_ : next_).packed.data() + s.firstByte;
        record.packed.insert(record.packed.end(), first, first + packedSizes_[i]);
        if (!kept) {
            tracedSegments_.emplace_back(nextFirstSegment_[i], s.segmentCount);
            tracedGroups_.push_back(s.group);
        }
        s.firstByte = std::uint32_t(at);
    }
    // The traced samples' units, and a superset of the kept ones' (read again only when
    // the cones are next built).
    record.unitMask |= nextUnitMask_ | old_->unitMask;
    return live;
}

bool BlockTracer::UpdateInPlace() {
    BlockRecord &r = *old_;
    if (!sameOrder_ || next_.samples.size() != r.samples.size() || !r.fansBuilt) return false;
    std::size_t fresh = 0;
    bool everythingReplaced = false, orderSensitiveReplaced = false;
    tracedSegments_.clear();
    tracedGroups_.clear();
    for (std::size_t i = 0; i < next_.samples.size(); ++i) {
        if (keptFromOld_[i]) continue;
        const StoredSample &traced = next_.samples[i];
        StoredSample &stored = r.samples[i];
        const bool storedHasSegments = stored.segmentCount != StoredSample::kEverything;
        const std::size_t oldBytes = r.SampleBytes(stored);
        everythingReplaced |= !storedHasSegments;
        orderSensitiveReplaced |= stored.orderSensitive && !traced.orderSensitive;
        r.hasOrderSensitive |= traced.orderSensitive;
        if (traced.segmentCount == StoredSample::kEverything) {
            r.deadBytes += oldBytes;
            stored = traced;
            r.hasEverything = true;
            AddToGroupIndex(r, stored);  // built with the cones, which an update in place needs
            continue;
        }
        const std::size_t newBytes = next_.SampleBytes(traced);
        std::size_t at = stored.firstByte;
        if (storedHasSegments && newBytes <= oldBytes) {
            r.deadBytes += oldBytes - newBytes;
        } else {
            r.deadBytes += oldBytes;
            at = r.packed.size();
            // An eighth more room, not double: a record is kept for the whole run.
            const std::size_t need = at + newBytes;
            if (need > r.packed.capacity()) r.packed.reserve(need + need / 8);
            r.packed.resize(need);
        }
        std::copy_n(next_.packed.data() + traced.firstByte, newBytes, r.packed.data() + at);
        stored = traced;
        stored.firstByte = std::uint32_t(at);
        AddToGroupIndex(r, stored);  // built with the cones, which an update in place needs
        fresh += traced.segmentCount;
        tracedSegments_.emplace_back(nextFirstSegment_[i], traced.segmentCount);
        tracedGroups_.push_back(traced.group);
    }
    r.unitMask |= nextUnitMask_;  // the traced samples'
    if (4 * r.deadBytes > r.packed.size()) CompactSegments(r);
    // A sample that depended on everything was traced again: is there another one left?
    if (everythingReplaced) {
        r.hasEverything = false;
        for (const StoredSample &s : r.samples) r.hasEverything |= s.segmentCount == StoredSample::kEverything;
    }
    if (orderSensitiveReplaced) {
        r.hasOrderSensitive = false;
        for (const StoredSample &s : r.samples) r.hasOrderSensitive |= s.orderSensitive;
    }
    std::copy(next_.pixels.begin(), next_.pixels.end(), r.pixels.begin());
    r.apexes = next_.apexes;
    // Grow the cones by what was traced anew, or leave them to be built afresh (as End).
    std::size_t live = 0;
    for (const StoredSample &s : r.samples)
        if (s.segmentCount != StoredSample::kEverything) live += s.segmentCount;
    if (r.ConesMayGrowBy(fresh, live)) {
        GrowRecordFans(r, nextSegments_.data(), nextFanOf_.data(), tracedSegments_, tracedGroups_);
        r.grownSegments += fresh;
    } else {
        r.fans = BlockFans();
        r.groupFans.clear();
        r.groupIndex.Clear();
        r.fansBuilt = false;
        r.grownSegments = 0;
    }
    return true;
}

void BlockTracer::CompactSegments(BlockRecord &record) {
    std::vector<std::uint8_t> packed;
    packed.reserve(record.packed.size() - record.deadBytes);
    for (StoredSample &s : record.samples) {
        if (s.segmentCount == StoredSample::kEverything) continue;
        const std::size_t at = packed.size();
        const std::uint8_t *first = record.packed.data() + s.firstByte;
        packed.insert(packed.end(), first, first + record.SampleBytes(s));
        s.firstByte = std::uint32_t(at);
    }
    record.packed.swap(packed);
    record.deadBytes = 0;
}

bool BlockTracer::ChangedRect(int &left, int &top, int &right, int &bottom) const {
    left = changed_[0];
    top = changed_[1];
    right = changed_[2];
    bottom = changed_[3];
    return left <= right && top <= bottom;
}

}  // namespace povrayfc
