// Recording ray segments into the pixel being traced, and shadow segments cut at a blocker.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "povrayfc/pixel_recorder.h"
#include "povrayfc/ray_recording.h"
#include "povrayfc/voxel_grid.h"

namespace povrayfc {
namespace {

const VoxelGrid kGrid(Box{Vec3{0, 0, 0}, Vec3{10, 1, 1}}, 10, 1, 1);
const double kOrigin[3] = {0.5, 0.5, 0.5}, kAlongX[3] = {1, 0, 0};

std::uint32_t MaxVoxel(const PixelRecorder &r) {
    return *std::max_element(r.Voxels().begin(), r.Voxels().end());
}

TEST(RayRecording, NothingIsRecordedOutsideARecordingThread) {
    PixelRecorder recorder;
    recorder.Begin();
    RecordRaySegment(kOrigin, kAlongX, 5.0);
    { ShadowSegmentRecord shadow(kOrigin, kAlongX, 5.0); }
    // Invariant: without StartRecordingRays the hooks do nothing.
    EXPECT_TRUE(recorder.Voxels().empty());
}

TEST(RayRecording, ShadowSegmentReachesTheLightOrStopsAtItsBlocker) {
    PixelRecorder recorder;
    recorder.Begin();
    StartRecordingRays(recorder, kGrid);
    { ShadowSegmentRecord shadow(kOrigin, kAlongX, 8.0); }
    // Invariant: an unblocked shadow test depends on every voxel up to the light.
    EXPECT_EQ(MaxVoxel(recorder), 8u);
    recorder.Begin();
    {
        ShadowSegmentRecord shadow(kOrigin, kAlongX, 8.0);
        shadow.BlockedAt(2.2);
        shadow.BlockedAt(std::nan(""));  // ignored
        shadow.BlockedAt(-1.0);          // ignored
        shadow.BlockedAt(6.0);           // farther than the nearest blocker: ignored
    }
    // Invariant: a blocked one depends only on the voxels up to the blocker (x = 2.7).
    EXPECT_EQ(MaxVoxel(recorder), 2u);
    StopRecordingRays();
}

TEST(RayRecording, NaNRayMakesThePixelDependOnEverything) {
    PixelRecorder recorder;
    recorder.Begin();
    StartRecordingRays(recorder, kGrid);
    const double nanDirection[3] = {std::nan(""), 0, 0};
    RecordRaySegment(kOrigin, nanDirection, 1.0);
    StopRecordingRays();
    // Invariant: a ray that cannot be placed in the grid is never silently dropped.
    EXPECT_TRUE(recorder.Everything());
}

}  // namespace
}  // namespace povrayfc
