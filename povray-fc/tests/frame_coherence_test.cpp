// The session's per-frame decisions, driven the way the POV-Ray hooks drive it.
#include <gtest/gtest.h>

#include "povrayfc/frame_coherence.h"
#include "povrayfc/ray_recording.h"

namespace povrayfc {
namespace {

const int kW = 4, kH = 1;
const void *const kScene = reinterpret_cast<const void *>(0x1234);

FrameSetup FrameSetupFor(int frame) {
    FrameSetup s;
    s.width = kW;
    s.height = kH;
    s.right = kW - 1;
    s.bottom = kH - 1;
    s.frameNumber = frame;
    s.gridResolution = 8;
    return s;
}

ObjectSignature Object(std::uint64_t hash, double x0, double x1) {
    ObjectSignature o;
    o.hash = hash;
    o.bounds = Box{Vec3{x0, 0, 0}, Vec3{x1, 1, 1}};
    return o;
}

SceneSignature Scene(std::vector<ObjectSignature> objects, std::uint64_t camera = 7) {
    SceneSignature s;
    s.camera = camera;
    s.objects = std::move(objects);
    s.complete = true;
    return s;
}

// Renders a frame as the trace tasks do: pixel x's single ray runs along y=0.5, z=0.5
// from x=0 up to x = 2x+1 (so pixel 0 sees [0,1], pixel 3 sees [0,7]).
int RenderFrame(FrameCoherence &fc) {
    int traced = 0;
    for (int x = 0; x < kW; ++x) {
        if (!fc.NeedsTrace(x, 0)) continue;
        fc.BeginRecording();
        const double origin[3] = {0.0, 0.5, 0.5}, dir[3] = {1.0, 0.0, 0.0};
        RecordRaySegment(origin, dir, 2.0 * x + 1.0);
        fc.CommitPixel(x, 0);
        const float colour[5] = {float(x), 0, 0, 0, 0};
        fc.StoreColour(x, 0, colour);
        ++traced;
    }
    fc.EndFrame(0);
    return traced;
}

void Begin(FrameCoherence &fc, int frame, SceneSignature scene, SceneEffects effects = {}) {
    PublishSceneSignature(kScene, std::move(scene));
    fc.BeginFrame(true, FrameSetupFor(frame), kScene, effects);
}

std::vector<ObjectSignature> Floor() { return {Object(1, 0, 8)}; }  // spans the grid

TEST(FrameCoherence, FirstFrameTracesEverythingThenNothingWhenUnchanged) {
    FrameCoherence &fc = FrameCoherence::Get();
    Begin(fc, 1, Scene(Floor()));
    ASSERT_TRUE(fc.Active());
    // Invariant: a new sequence has nothing to reuse.
    EXPECT_EQ(RenderFrame(fc), kW);
    EXPECT_EQ(fc.LastStats().fullReason, "first frame");
    Begin(fc, 2, Scene(Floor()));
    // Invariant: an identical scene re-traces no pixel and keeps the stored colours.
    EXPECT_EQ(RenderFrame(fc), 0);
    float c[5];
    fc.StoredColour(3, 0, c);
    EXPECT_EQ(c[0], 3.0f);
}

TEST(FrameCoherence, MovedObjectDirtiesOnlyPixelsWhoseRaysCrossedIt) {
    FrameCoherence &fc = FrameCoherence::Get();
    std::vector<ObjectSignature> before = Floor(), after = Floor();
    before.push_back(Object(50, 5.2, 5.8));
    after.push_back(Object(51, 6.2, 6.8));
    Begin(fc, 1, Scene(before));
    RenderFrame(fc);
    Begin(fc, 2, Scene(after));
    // Invariant: pixels 0..1 reach x<=3 only, so they stay clean; pixel 3 reaches x=7.
    EXPECT_FALSE(fc.NeedsTrace(0, 0));
    EXPECT_FALSE(fc.NeedsTrace(1, 0));
    EXPECT_TRUE(fc.NeedsTrace(3, 0));
    RenderFrame(fc);
}

TEST(FrameCoherence, DuplicateObjectsAreMatchedAsAMultiset) {
    FrameCoherence &fc = FrameCoherence::Get();
    std::vector<ObjectSignature> two = Floor(), one = Floor();
    two.push_back(Object(60, 6.5, 7.0));
    two.push_back(Object(60, 6.5, 7.0));
    one.push_back(Object(60, 6.5, 7.0));
    Begin(fc, 1, Scene(two));
    RenderFrame(fc);
    Begin(fc, 2, Scene(one));
    // Invariant: removing one of two identical objects is a change where they were.
    EXPECT_TRUE(fc.NeedsTrace(3, 0));
    EXPECT_FALSE(fc.NeedsTrace(0, 0));
    RenderFrame(fc);
}

TEST(FrameCoherence, CameraChangeStartsANewSequence) {
    FrameCoherence &fc = FrameCoherence::Get();
    Begin(fc, 1, Scene(Floor(), 7));
    RenderFrame(fc);
    Begin(fc, 2, Scene(Floor(), 8));
    EXPECT_EQ(RenderFrame(fc), kW);
    EXPECT_NE(fc.LastStats().fullReason.find("camera"), std::string::npos);
}

TEST(FrameCoherence, UnboundedChangeRendersTheWholeFrame) {
    FrameCoherence &fc = FrameCoherence::Get();
    Begin(fc, 1, Scene(Floor()));
    RenderFrame(fc);
    std::vector<ObjectSignature> objects = Floor();
    ObjectSignature plane;
    plane.hash = 99;
    plane.infinite = true;
    objects.push_back(plane);
    Begin(fc, 2, Scene(objects));
    EXPECT_EQ(RenderFrame(fc), kW);
    EXPECT_FALSE(fc.LastStats().fullReason.empty());
}

TEST(FrameCoherence, InexactEffectMakesTheFrameInactiveAndSaysWhich) {
    FrameCoherence &fc = FrameCoherence::Get();
    SceneEffects effects;
    effects.radiosity = true;
    Begin(fc, 1, Scene(Floor()), effects);
    // Invariant: an effect fc cannot keep exact renders exactly as POV-Ray, tracking nothing.
    EXPECT_FALSE(fc.Active());
    fc.EndFrame(0);
    EXPECT_NE(fc.LastStats().fullReason.find("radiosity"), std::string::npos);
}

TEST(FrameCoherence, OffForgetsEverything) {
    FrameCoherence &fc = FrameCoherence::Get();
    Begin(fc, 1, Scene(Floor()));
    RenderFrame(fc);
    PublishSceneSignature(kScene, Scene(Floor()));
    fc.BeginFrame(false, FrameSetupFor(2), kScene, {});
    EXPECT_FALSE(fc.Active());
    fc.EndFrame(0);
    Begin(fc, 3, Scene(Floor()));
    // Invariant: after an fc-off frame nothing stored is trusted.
    EXPECT_EQ(RenderFrame(fc), kW);
}

}  // namespace
}  // namespace povrayfc
