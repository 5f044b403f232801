// Recording of ray segments into the camera sample a render thread is tracing.
//
// POV-Ray's tracing code calls RecordRaySegment() for every ray it traces (camera,
// anti-aliasing, reflected, refracted, continued and shadow rays). When the thread is
// not recording (fc off, or a frame fc renders without recording) the call is one
// thread-local load and a branch, so the hooks stay in the hot path unconditionally.
// When it is, the segment is appended to the sample's list as 32 bytes, with the id of the
// unit it ended on: nothing is walked or looked up while tracing (a voxel walk per ray
// used to cost three times the ray itself); the next frame tests the stored segments
// against what changed.
#ifndef POVRAYFC_RAY_RECORDING_H
#define POVRAYFC_RAY_RECORDING_H

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "povrayfc/scene_signature.h"
#include "povrayfc/segment.h"

namespace povrayfc {

// The points a render block's segments are bundled by (see segment_fans.h): the camera
// position its camera rays start from, and the light positions its shadow rays aim at.
// Filled as rays are recorded; index = the bundle's fan number.
//
// Each light has two bundles: the shadow rays from the surfaces the block's camera rays
// hit, and the "deep" ones, from where its reflected and refracted rays hit. The first
// come from neighbouring points and make a narrow cone; the second come from anywhere a
// curved mirror looks, and their cone spans tens of degrees. In one bundle, that wide
// cone reached every change near the block and every shadow ray of it was tested: on
// Newton's cradle nine in ten of those tests found nothing.
struct FanApexes {
    static constexpr int kMax = 16;  // the camera and seven lights, each twice
    double point[kMax][3];
    bool isOrigin[kMax];
    bool isDeep[kMax];
    int count = 0;

    void Clear() { count = 0; }
    // The fan of a segment starting at `origin`: the block's first recorded origin (its
    // first camera ray's) is fan 0; other origins are loose.
    std::uint8_t OriginFan(const double origin[3]) {
        if (count == 0) {
            Set(0, origin, true);
            count = 1;
        }
        return (isOrigin[0] && Same(point[0], origin)) ? 0 : kLoose;
    }
    // The fan of a shadow segment aimed at `aim` (the light point it tests, as origin +
    // depth * direction: the same light gives points a few ulps apart, hence the
    // tolerance; how far each segment really strays from its apex is measured when the
    // cones are built).
    // `deep`: the ray leaves a point a reflected or refracted ray hit.
    std::uint8_t AimFan(const double aim[3], bool deep = false) {
        for (int i = 0; i < count; ++i)
            if (!isOrigin[i] && isDeep[i] == deep && Near(point[i], aim)) return std::uint8_t(i);
        if (count == kMax) return kLoose;
        Set(count, aim, false);
        isDeep[count] = deep;
        return std::uint8_t(count++);
    }

    static constexpr std::uint8_t kLoose = 0xff;

  private:
    static bool Same(const double *a, const double *b) { return a[0] == b[0] && a[1] == b[1] && a[2] == b[2]; }
    static bool Near(const double *a, const double *b) {
        const double tolerance = 1e-6 * (1.0 + std::fabs(a[0]) + std::fabs(a[1]) + std::fabs(a[2]));
        return std::fabs(a[0] - b[0]) <= tolerance && std::fabs(a[1] - b[1]) <= tolerance &&
               std::fabs(a[2] - b[2]) <= tolerance;
    }
    void Set(int i, const double *p, bool origin) {
        point[i][0] = p[0];
        point[i][1] = p[1];
        point[i][2] = p[2];
        isOrigin[i] = origin;
        isDeep[i] = false;
    }
};

// Collects the segments of one camera sample, appending to a render block's lists (so a
// finished sample needs no copy): each segment and its fan number.
class SampleRecorder {
  public:
    // Starts a sample whose segments go to the end of `segments` (and their fans to
    // `fanOf`, against the block's `apexes`). `unitIds[i]` is the id of the frame's unit i
    // (unit_ids.h), for `unitCount` units.
    void Begin(std::vector<Segment> &segments, std::vector<std::uint8_t> &fanOf, FanApexes &apexes,
               const std::uint32_t *unitIds, std::size_t unitCount) {
        segments_ = &segments;
        fanOf_ = &fanOf;
        apexes_ = &apexes;
        unitIds_ = unitIds;
        unitCount_ = unitCount;
        first_ = segments.size();
        everything_ = false;
        deep_ = false;
        orderSensitive_ = false;
    }
    // A ray that ended on the frame's unit `unit` (the index the parser wrote into what it
    // hit, or kUnitNothing).
    void Add(const double origin[3], const double direction[3], double tmax, std::uint32_t unit) {
        Segment s;
        if (!MakeSegment(origin, direction, tmax, s)) {
            everything_ = true;  // a ray that cannot be placed: any change must re-trace it
            return;
        }
        s.unit = UnitId(unit);
        segments_->push_back(s);
        const std::uint8_t fan = apexes_->OriginFan(origin);
        fanOf_->push_back(fan);
        // POV-Ray records a ray when it found what the ray hits, and lights a point
        // (its shadow tests) before it follows the reflected and refracted rays: shadow
        // rays after a ray that did not start at the camera leave the points such rays
        // hit. (Which bundle a segment joins never changes a pixel, only how tight the
        // cones are.)
        deep_ |= fan == FanApexes::kLoose;
    }
    // A shadow ray towards the light point `aim` (reaching it, or stopped short by tmax).
    // `opaqueBlocker`: an opaque surface of `unit` ended the test (kOpaqueBlocker).
    void AddAimed(const double origin[3], const double direction[3], double tmax, const double aim[3],
                  std::uint32_t unit, bool opaqueBlocker = false) {
        Segment s;
        if (!MakeSegment(origin, direction, tmax, s)) {
            everything_ = true;
            return;
        }
        s.unit = UnitId(unit);
        if (opaqueBlocker && s.unit != Segment::kNoUnit) s.unit |= Segment::kOpaqueBlocker;
        segments_->push_back(s);
        fanOf_->push_back(apexes_->AimFan(aim, deep_));
    }
    // Drops the segments recorded after the sample's first `count` (a shadow test's pieces
    // that its opaque blocker made moot).
    void KeepFirst(std::size_t count) {
        segments_->resize(first_ + count);
        fanOf_->resize(first_ + count);
    }
    void MarkEverything() { everything_ = true; }
    // One of the sample's searches for a nearest intersection ended in a tie that the order
    // of the scene's objects decided (tie_watch.h).
    void MarkOrderSensitive() { orderSensitive_ = true; }

    bool Everything() const { return everything_; }
    bool OrderSensitive() const { return orderSensitive_; }
    std::size_t First() const { return first_; }
    std::size_t Count() const { return segments_->size() - first_; }
    // Drops the sample's segments (it depends on everything anyway).
    void Discard() {
        segments_->resize(first_);
        fanOf_->resize(first_);
    }

  private:
    // The id a segment that ended on the frame's unit `unit` records. An object the parser
    // gave no unit makes the sample depend on everything.
    std::uint32_t UnitId(std::uint32_t unit) {
        if (unit == kUnitNothing) return Segment::kNoUnit;
        if (unit < unitCount_ && unitIds_[unit] < Segment::kOpaqueBlocker) return unitIds_[unit];
        everything_ = true;
        return Segment::kNoUnit;
    }

    std::vector<Segment> *segments_ = nullptr;
    std::vector<std::uint8_t> *fanOf_ = nullptr;
    FanApexes *apexes_ = nullptr;
    const std::uint32_t *unitIds_ = nullptr;
    std::size_t unitCount_ = 0;
    std::size_t first_ = 0;
    bool everything_ = false;
    bool deep_ = false;  // a reflected or refracted ray was recorded in this sample
    bool orderSensitive_ = false;
};

namespace detail {
extern thread_local SampleRecorder *tlsRecorder;
}  // namespace detail

// Adds the segment origin + t*direction, t in [0, tmax], to the sample being recorded on
// this thread. tmax may be huge or infinite (a ray that hit nothing); `unit` is the index
// the parser wrote into the object the ray ended on, or kUnitNothing.
inline void RecordRaySegment(const double origin[3], const double direction[3], double tmax, std::uint32_t unit) {
    if (detail::tlsRecorder) detail::tlsRecorder->Add(origin, direction, tmax, unit);
}

// A shadow test's segments, in pieces: up to each transparent object the test passes
// (PassedAt, which shaped the light's colour there), and the last one to the light or to
// the blocker that answered (BlockedAt), recorded when the test returns. POV-Ray's shadow
// loop moves its ray's origin past each transparent object and shortens the remaining
// depth by as much: this reads both where they live.
//
// An opaque blocker (OPAQUE_FLAG) darkens the light exactly, whatever lies before or
// beyond it: the test is then one kOpaqueBlocker segment, from the loop's last origin over
// the whole depth the test looked up to, and its pieces are dropped. It holds for as long
// as that unit, or another opaque solid, still crosses it (shadow_blockers.h); nothing
// else can change its answer, so no hull is tested against it.
// Costs one thread-local test when the thread is not recording.
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
        if (!recorder_) return;
        if (!blocked_ || !opaque_ || blocker_ == kUnitNothing) {
            recorder_->AddAimed(origin_, direction_, blocked_ ? blockedAt_ : depth_, aim_, blocker_);
            return;
        }
        if (recorder_->Count() >= before_) recorder_->KeepFirst(before_);
        recorder_->AddAimed(origin_, direction_, depth_ - projected_, aim_, blocker_, true);
    }
    ShadowSegmentRecord(const ShadowSegmentRecord &) = delete;
    ShadowSegmentRecord &operator=(const ShadowSegmentRecord &) = delete;

    // A light with projected_through: the test ignores surfaces within `depth` of the light.
    void ProjectedDepth(double depth) { projected_ = depth; }
    // The test passed a transparent object (the frame's unit `unit`) at `distance` from the
    // current origin; before the loop moves its origin there.
    void PassedAt(double distance, std::uint32_t unit) {
        if (recorder_) recorder_->AddAimed(origin_, direction_, distance, aim_, unit);
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
};

// Routes this thread's RecordRaySegment() calls into `recorder` until StopRecordingRays().
inline void StartRecordingRays(SampleRecorder &recorder) { detail::tlsRecorder = &recorder; }
inline void StopRecordingRays() { detail::tlsRecorder = nullptr; }

}  // namespace povrayfc

#endif
