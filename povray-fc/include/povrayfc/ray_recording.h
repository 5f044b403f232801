// Recording of ray segments into the dependencies of the pixel a render thread traces.
//
// POV-Ray's tracing code calls RecordRaySegment() for every ray it traces (camera,
// anti-aliasing, reflected, refracted, continued and shadow rays). The call costs one
// thread-local load when the thread is not recording (fc off, or a frame fc renders
// in full without tracking), so the hooks stay in the hot path unconditionally.
#ifndef POVRAYFC_RAY_RECORDING_H
#define POVRAYFC_RAY_RECORDING_H

namespace povrayfc {

class PixelRecorder;
class VoxelGrid;

namespace detail {
extern thread_local PixelRecorder *tlsRecorder;
void RecordSegment(const double origin[3], const double direction[3], double tmax);
}  // namespace detail

// Adds every voxel the segment origin + t*direction, t in [0, tmax], touches to the
// pixel being recorded on this thread. tmax may be huge or infinite (a ray that hit
// nothing): the segment is clipped to the grid.
inline void RecordRaySegment(const double origin[3], const double direction[3], double tmax) {
    if (detail::tlsRecorder) detail::RecordSegment(origin, direction, tmax);
}

// A shadow test's segment, recorded when the test returns: to the light, or only up to
// a fully opaque blocker when the test found one (BlockedAt), since nothing beyond it
// can change the answer. Costs one thread-local test when the thread is not recording.
class ShadowSegmentRecord {
  public:
    ShadowSegmentRecord(const double origin[3], const double direction[3], double depth)
        : active_(detail::tlsRecorder != nullptr), depth_(depth), reach_(depth) {
        if (!active_) return;
        for (int i = 0; i < 3; ++i) {
            origin_[i] = origin[i];
            direction_[i] = direction[i];
        }
    }
    ~ShadowSegmentRecord() {
        if (active_) detail::RecordSegment(origin_, direction_, reach_);
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
    bool active_;
    double origin_[3] = {0, 0, 0}, direction_[3] = {0, 0, 0};
    double depth_, reach_;
};

// Routes this thread's RecordRaySegment() calls into `recorder`, walking `grid`,
// until StopRecordingRays().
void StartRecordingRays(PixelRecorder &recorder, const VoxelGrid &grid);
void StopRecordingRays();

}  // namespace povrayfc

#endif
