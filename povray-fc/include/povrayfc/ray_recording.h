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

// Routes this thread's RecordRaySegment() calls into `recorder`, walking `grid`,
// until StopRecordingRays().
void StartRecordingRays(PixelRecorder &recorder, const VoxelGrid &grid);
void StopRecordingRays();

}  // namespace povrayfc

#endif
