// Recording of ray segments into the camera sample a render thread is tracing.
//
// POV-Ray's tracing code calls RecordRaySegment() for every ray it traces (camera,
// anti-aliasing, reflected, refracted, continued and shadow rays). When the thread is
// not recording (fc off, or a frame fc renders without recording) the call is one
// thread-local load and a branch, so the hooks stay in the hot path unconditionally.
// When it is, the segment is appended to the sample's list as 28 bytes: nothing is
// walked or looked up while tracing (a voxel walk per ray used to cost three times the
// ray itself); the next frame tests the stored segments against what changed.
#ifndef POVRAYFC_RAY_RECORDING_H
#define POVRAYFC_RAY_RECORDING_H

#include <cstddef>
#include <vector>

#include "povrayfc/segment.h"

namespace povrayfc {

// Collects the segments of one camera sample, appending to a caller's vector (a block's
// segment list, so that a finished sample needs no copy).
class SampleRecorder {
  public:
    // Starts a sample whose segments go to the end of `segments`.
    void Begin(std::vector<Segment> &segments) {
        segments_ = &segments;
        first_ = segments.size();
        everything_ = false;
    }
    void Add(const double origin[3], const double direction[3], double tmax) {
        Segment s;
        if (MakeSegment(origin, direction, tmax, s))
            segments_->push_back(s);
        else
            everything_ = true;  // a ray that cannot be placed: any change must re-trace it
    }
    void MarkEverything() { everything_ = true; }

    bool Everything() const { return everything_; }
    std::size_t First() const { return first_; }
    std::size_t Count() const { return segments_->size() - first_; }

  private:
    std::vector<Segment> *segments_ = nullptr;
    std::size_t first_ = 0;
    bool everything_ = false;
};

namespace detail {
extern thread_local SampleRecorder *tlsRecorder;
}  // namespace detail

// Adds the segment origin + t*direction, t in [0, tmax], to the sample being recorded on
// this thread. tmax may be huge or infinite (a ray that hit nothing).
inline void RecordRaySegment(const double origin[3], const double direction[3], double tmax) {
    if (detail::tlsRecorder) detail::tlsRecorder->Add(origin, direction, tmax);
}

// A shadow test's segment, recorded when the test returns: to the light, or only up to
// a fully opaque blocker when the test found one (BlockedAt), since nothing beyond it
// can change the answer. Costs one thread-local test when the thread is not recording.
class ShadowSegmentRecord {
  public:
    ShadowSegmentRecord(const double origin[3], const double direction[3], double depth)
        : recorder_(detail::tlsRecorder), depth_(depth), reach_(depth) {
        if (!recorder_) return;
        for (int i = 0; i < 3; ++i) {
            origin_[i] = origin[i];
            direction_[i] = direction[i];
        }
    }
    ~ShadowSegmentRecord() {
        if (recorder_) recorder_->Add(origin_, direction_, reach_);
    }
    ShadowSegmentRecord(const ShadowSegmentRecord &) = delete;
    ShadowSegmentRecord &operator=(const ShadowSegmentRecord &) = delete;

    // The depth the test started with (distance to the light along direction).
    double Depth() const { return depth_; }
    // An opaque blocker at `distance` from the original origin answered the test.
    void BlockedAt(double distance) {
        if (distance >= 0.0 && distance < reach_) reach_ = distance;
    }

  private:
    SampleRecorder *recorder_;
    double origin_[3] = {0, 0, 0}, direction_[3] = {0, 0, 0};
    double depth_, reach_;
};

// Routes this thread's RecordRaySegment() calls into `recorder` until StopRecordingRays().
inline void StartRecordingRays(SampleRecorder &recorder) { detail::tlsRecorder = &recorder; }
inline void StopRecordingRays() { detail::tlsRecorder = nullptr; }

}  // namespace povrayfc

#endif
