// Thread-local recording of ray segments through the voxel grid.
#include "povrayfc/ray_recording.h"

#include "povrayfc/pixel_recorder.h"
#include "povrayfc/segment_walker.h"
#include "povrayfc/voxel_grid.h"

namespace povrayfc {
namespace detail {

thread_local PixelRecorder *tlsRecorder = nullptr;
thread_local const VoxelGrid *tlsGrid = nullptr;

void RecordSegment(const double origin[3], const double direction[3], double tmax) {
    PixelRecorder &recorder = *tlsRecorder;
    SegmentWalker walker(*tlsGrid, Vec3{origin[0], origin[1], origin[2]},
                         Vec3{direction[0], direction[1], direction[2]}, 0.0, tmax);
    if (!walker.Valid()) {
        // A NaN ray cannot be placed in the grid: the pixel must be re-traced
        // whenever anything changes.
        recorder.MarkEverything();
        return;
    }
    std::uint32_t voxel;
    while (walker.Next(voxel)) recorder.Add(voxel);
}

}  // namespace detail

void StartRecordingRays(PixelRecorder &recorder, const VoxelGrid &grid) {
    detail::tlsGrid = &grid;
    detail::tlsRecorder = &recorder;
}

void StopRecordingRays() {
    detail::tlsRecorder = nullptr;
    detail::tlsGrid = nullptr;
}

}  // namespace povrayfc
