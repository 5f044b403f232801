// The session and the block tracer driven the way the patched trace task drives them, on a
// toy renderer with neighbour-dependent anti-aliasing: every frame rendered with frame
// coherence must equal the same frame rendered from scratch, bit for bit.
#include <cmath>
#include <cstring>
#include <vector>

#include <gtest/gtest.h>

#include "povrayfc/block_tracer.h"
#include "povrayfc/frame_coherence.h"
#include "povrayfc/ray_recording.h"
#include "povrayfc/tie_watch.h"

namespace povrayfc {
namespace {

const int kW = 16, kH = 8, kBlock = 4;
const void *const kScene = reinterpret_cast<const void *>(0x1234);
const double kUp[3] = {0, 1, 0};

struct ToyBox {
    std::uint64_t id;
    Box box;
    // Glass (above 0): camera rays pass it, and each of its surfaces a shadow test crosses
    // scales the light by this; its id must then say its tint (the id is its appearance).
    float tint = 0.0f;
};

struct ToyScene {
    std::vector<ToyBox> boxes;
    double lightY = 50;
    std::uint64_t camera = 7;
    // Shadow tests are the loop through glass (TraceToyGlassShadow), whether or not a glass
    // box is there; the toy's other effects (its mirror) are left out then.
    bool glassShadows = false;
};

// Slab test; returns the entry distance or -1.
double Hit(const ToyBox &b, const double o[3], const double d[3]) {
    double t0 = 1e-9, t1 = 1e30;
    for (int a = 0; a < 3; ++a) {
        if (d[a] == 0) {
            if (o[a] < b.box.lo[a] || o[a] > b.box.hi[a]) return -1;
            continue;
        }
        double ta = (b.box.lo[a] - o[a]) / d[a], tb = (b.box.hi[a] - o[a]) / d[a];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
    }
    return t0 <= t1 ? t0 : -1;
}

// The unit a box is, as the parser numbers them: its place in the scene.
std::uint32_t UnitOf(const ToyScene &scene, const ToyBox *box) {
    return box ? std::uint32_t(box - scene.boxes.data()) : kUnitNothing;
}

// The toy's search for a camera ray's nearest box, nearer than `best`: like POV-Ray, the
// first of two boxes at the same depth wins, here in scene order.
void NearestBox(const ToyScene &scene, const double o[3], const double d[3], double &best, const ToyBox *&hit) {
    for (const ToyBox &b : scene.boxes) {
        if (b.tint > 0.0f) continue;
        const double t = Hit(b, o, d);
        if (t < 0) continue;
        NoteTieCandidate(t);
        if (t < best) best = t, hit = &b;
    }
}

constexpr std::uint8_t kToyCameraSearch = 1;  // the one search kind the toy can run again

// What the watch of the toy's camera search asks about it when it was tied (as
// fc-scene's SearchTieWatch answers for POV-Ray's): a box's id stands for its own hash.
struct ToySearch {
    const ToyScene *scene;
    const double *origin;
    const ToyBox *const *hit;
};
bool DescribeToySearch(const void *context, TiedSearch &search, std::uint32_t &unitIndex) {
    const ToySearch &toy = *static_cast<const ToySearch *>(context);
    search.kind = kToyCameraSearch;
    search.rayFlags = 0;
    for (int i = 0; i < 3; ++i) search.origin[i] = toy.origin[i];
    unitIndex = UnitOf(*toy.scene, *toy.hit);
    search.objectHash = *toy.hit ? (*toy.hit)->id : 0;
    return true;
}

// Whether the toy keeps its glass shadow tests' inputs while recording, and whether it says
// a shadow cache held an object as they started.
bool toyKeepsShadowTests = true, toyCacheHeld = false;

// The toy's shadow loop straight up from `origin`, as POV-Ray's: to the nearest surface
// farther than a tolerance; glass scales `light` and the loop goes on from that surface, an
// opaque box ends it dark. With `record`, tells it what it passed and what blocked it.
void ToyShadowLoop(const ToyScene &scene, double origin[3], double &depth, float light[3], ShadowSegmentRecord *record,
                   std::uint32_t *blockedBy = nullptr) {
    const double up[3] = {0, 1, 0};
    for (;;) {
        const ToyBox *nearest = nullptr;
        double at = depth;
        for (const ToyBox &b : scene.boxes) {
            // Both surfaces along +y, with the box's x and z extent.
            if (origin[0] < b.box.lo.x || origin[0] > b.box.hi.x || origin[2] < b.box.lo.z || origin[2] > b.box.hi.z) continue;
            for (double t : {b.box.lo.y - origin[1], b.box.hi.y - origin[1]})
                if (t > 1e-6 && t < at) at = t, nearest = &b;
        }
        if (!nearest) return;
        const std::uint32_t unit = UnitOf(scene, nearest);
        if (nearest->tint <= 0.0f) {
            light[0] = light[1] = light[2] = 0.0f;
            if (record) record->BlockedAt(at, unit, true);
            if (blockedBy) *blockedBy = unit;
            return;
        }
        if (record) record->PassedAt(at, unit);
        for (int i = 0; i < 3; ++i) light[i] *= nearest->tint;
        origin[1] += at;
        depth -= at;
    }
}

// With glass in the scene, a sample's shadow test is POV-Ray's loop, recorded in pieces
// (ShadowSegmentRecord), from just in front of the surface the camera ray hit.
void TraceToyGlassShadow(const ToyScene &scene, const ToyBox *hit, double x, double y, double best, float rgbft[5]) {
    double origin[3] = {x, y, -10 + best - 1e-3};
    double depth = scene.lightY - y;
    float light[3] = {1.0f, 1.0f, 1.0f};
    {
        ShadowSegmentRecord record(origin, kUp, depth);
        if (toyKeepsShadowTests) record.LightColour(light);
        record.CacheHeld(toyCacheHeld);
        ToyShadowLoop(scene, origin, depth, light, &record);
        if (record.Wanted()) record.Describe(0, 0, 1);
    }
    rgbft[0] = float(hit->id);
    rgbft[1] = light[0];
}

// The signature of what the toy's camera search found, as its shading reads it: whether it
// hit, the depth, and the box (its place, which the shadow ray passes over, and its id).
std::uint64_t ToyHitSignature(const ToyScene &scene, const ToyBox *hit, double best) {
    SignatureHash hash;
    hash.Add(hit != nullptr);
    if (hit) {
        hash.Add(best);
        hash.Add(hit->id);
        hash.Add(UnitOf(scene, hit));
    }
    return hash.Value();
}

// One camera sample at image position (x, y): a ray along +z, the box it hits, and a
// shadow ray from there straight up to the light (to the nearest box in its way). Records
// the rays like POV-Ray's hooks, each with the unit it ended on.
void TraceToy(const ToyScene &scene, double x, double y, float rgbft[5]) {
    const double o[3] = {x, y, -10}, d[3] = {0, 0, 1};
    double best = 1e30;
    const ToyBox *hit = nullptr;
    {
        const ToySearch search{&scene, o, &hit};
        TieWatch ties(d, best, &DescribeToySearch, &search);
        NearestBox(scene, o, d, best, hit);
    }
    if (RecordRaySegment(o, d, hit ? best : 2e10, UnitOf(scene, hit))) {
        SurfaceHit kept;
        std::copy(o, o + 3, kept.origin);
        std::copy(d, d + 3, kept.direction);
        kept.signature = ToyHitSignature(scene, hit, best);
        RecordSurfaceHit(kept);
    }
    std::memset(rgbft, 0, 5 * sizeof(float));
    if (!hit) return;
    if (scene.glassShadows) {
        TraceToyGlassShadow(scene, hit, x, y, best, rgbft);
        return;
    }
    const double p[3] = {x, y, -10 + best}, up[3] = {0, 1, 0};
    const double toLight = scene.lightY - p[1];
    const ToyBox *blocker = nullptr;
    double blockedAt = toLight;
    for (const ToyBox &b : scene.boxes) {
        const double t = (&b == hit) ? -1 : Hit(b, p, up);
        if (t >= 0 && t < blockedAt) blocker = &b, blockedAt = t;
    }
    const bool shadow = blocker != nullptr;
    RecordRaySegment(p, up, blockedAt, UnitOf(scene, blocker));
    rgbft[0] = float(hit->id);
    rgbft[1] = shadow ? 0.25f : 1.0f;
    if (hit->id == 1) {
        // The back wall is a mirror tilted up and to the side: a loose reflection ray.
        const double r[3] = {0.3, 0.4, -0.866};
        double rbest = 1e30;
        const ToyBox *rhit = nullptr;
        {
            TieWatch ties(r, rbest);
            for (const ToyBox &b : scene.boxes) {
                const double t = (&b == hit) ? -1 : Hit(b, p, r);
                if (t < 0) continue;
                NoteTieCandidate(t);
                if (t < rbest) rbest = t, rhit = &b;
            }
        }
        RecordRaySegment(p, r, rhit ? rbest : 2e10, UnitOf(scene, rhit));
        rgbft[2] = rhit ? float(rhit->id) : 0.5f;
    }
}

// The toy's camera search run again in the frame being rendered, as the patch layer runs
// POV-Ray's (the reflection's search is not described: never run again).
class ToyReplayer : public TieReplayer {
  public:
    explicit ToyReplayer(const ToyScene &scene) : scene_(scene) {}
    bool Replay(const TiedSearch &search, double &depth, std::uint32_t &unitIndex, std::uint64_t &objectHash) override {
        if (search.kind != kToyCameraSearch) return false;
        depth = search.start;
        const ToyBox *hit = nullptr;
        NearestBox(scene_, search.origin, search.direction, depth, hit);
        unitIndex = UnitOf(scene_, hit);
        objectHash = hit ? hit->id : 0;
        return true;
    }

  private:
    const ToyScene &scene_;
};

// The toy's glass shadow test run again in the frame being rendered, as the patch layer runs
// POV-Ray's. `lies`: it answers the colour kept, whatever the loop gives (the rule made
// blind, for the tests that must catch it).
class ToyShadowReplayer : public ShadowReplayer {
  public:
    explicit ToyShadowReplayer(const ToyScene &scene) : scene_(scene) {}
    bool Replay(const ShadowTest &test, float colourOut[3], ShadowRun &run) override {
        ++runs;
        double origin[3] = {test.origin[0], test.origin[1], test.origin[2]};
        double depth = test.depth;
        std::copy(test.colourIn, test.colourIn + 3, colourOut);
        ToyShadowLoop(scene_, origin, depth, colourOut, nullptr, &run.blocker);
        run.passed = depth != test.depth;
        // As POV-Ray's loop, it caches an opaque blocker it met before anything it passed.
        run.cached = run.blocker != kUnitNothing && !run.passed;
        if (lies) std::copy(test.colourOut, test.colourOut + 3, colourOut);
        return true;
    }
    static inline int runs = 0;
    static inline bool lies = false;

  private:
    const ToyScene &scene_;
};

// The toy's camera search run again in the frame being rendered, with the signature of what
// it finds, as the patch layer runs POV-Ray's. `lies`: it answers the signature kept (the
// rule made blind, for the tests that must catch it).
class ToySurfaceReplayer : public SurfaceReplayer {
  public:
    explicit ToySurfaceReplayer(const ToyScene &scene) : scene_(scene) {}
    bool Replay(const SurfaceHit &hit, std::uint64_t &signature, std::uint32_t &unitIndex) override {
        ++runs;
        double best = 1e30;
        const ToyBox *box = nullptr;
        NearestBox(scene_, hit.origin, hit.direction, best, box);
        signature = lies ? hit.signature : ToyHitSignature(scene_, box, best);
        unitIndex = UnitOf(scene_, box);
        return true;
    }
    static inline int runs = 0;
    static inline bool lies = false;

  private:
    const ToyScene &scene_;
};

// Whether RenderFc gives its tracer replayers (as the patched trace task does), and among
// them one for surface hits.
bool toyReplays = true, toySurfaceReplays = true;
// Whether the toy's shadow caches may hold a filtering object (SetShadowReplayer): where
// not, tests an opaque box answered are kept too.
bool toyShadowCachesMatter = true;

using Image = std::vector<float>;  // 5 floats a pixel

// AA in the manner of POV-Ray's method 1: a pixel that differs from its left neighbour
// (the block's left border sample for the first column) is supersampled.
template <class Sample>
void RenderBlock(int left, int top, int right, int bottom, Sample sample, Image &out) {
    for (int y = top; y <= bottom; ++y) {
        float prev[5];
        sample(double(left) - 1.0, double(y), prev);
        for (int x = left; x <= right; ++x) {
            float c[5];
            sample(double(x), double(y), c);
            float *px = &out[(std::size_t(y) * kW + x) * 5];
            std::memcpy(px, c, sizeof c);
            if (c[0] != prev[0] || c[1] != prev[1]) {
                for (int s = 0; s < 4; ++s) {
                    float sub[5];
                    sample(x + ((s & 1) ? 0.25 : -0.25), y + ((s & 2) ? 0.25 : -0.25), sub);
                    for (int k = 0; k < 5; ++k) px[k] += sub[k];
                }
                for (int k = 0; k < 5; ++k) px[k] /= 5.0f;
            }
            std::memcpy(prev, c, sizeof c);
        }
    }
}

// Each box is an item and a unit: its id is its appearance, its box its geometry.
SceneSignature Signature(const ToyScene &scene) {
    SceneSignature s;
    s.camera = scene.camera;
    s.lights = std::uint64_t(scene.lightY * 1000);
    for (const ToyBox &b : scene.boxes) {
        UnitSignature u;
        u.geometry = std::uint64_t(std::llround(b.box.lo.x * 1024)) * 31 ^ std::uint64_t(std::llround(b.box.lo.y * 1024)) * 17 ^
                     std::uint64_t(std::llround(b.box.lo.z * 1024)) ^ std::uint64_t(std::llround(b.box.hi.x * 1024)) * 7 ^
                     std::uint64_t(std::llround(b.box.hi.y * 1024)) * 13 ^ std::uint64_t(std::llround(b.box.hi.z * 1024)) * 3;
        u.hash = b.id * 1000003u ^ u.geometry;
        u.bounds = b.box;
        s.units.push_back(u);
        ObjectSignature o;
        o.hash = u.hash;
        o.bounds = b.box;
        s.objects.push_back(o);
    }
    s.complete = true;
    return s;
}

FrameSetup ToySetup(int frame, int threads = 1) {
    FrameSetup s;
    s.width = kW;
    s.height = kH;
    s.right = kW - 1;
    s.bottom = kH - 1;
    s.samplingMethod = 1;
    s.blockSize = kBlock;
    s.frameNumber = frame;
    s.renderThreads = threads;
    return s;
}

Image RenderFull(const ToyScene &scene) {
    Image img(std::size_t(kW) * kH * 5, 0.0f);
    for (int by = 0; by < kH; by += kBlock)
        for (int bx = 0; bx < kW; bx += kBlock)
            RenderBlock(bx, by, bx + kBlock - 1, by + kBlock - 1,
                        [&](double x, double y, float c[5]) { TraceToy(scene, x, y, c); }, img);
    return img;
}

struct FcResult {
    Image image;
    std::uint64_t tracedSamples = 0;
    std::uint64_t changedPixels = 0;   // ChangedCount over the traced blocks
    std::uint64_t changedRectArea = 0; // the area of their ChangedRect
    bool stored = false;               // a store was kept (recording not paused)
    std::size_t storeBytes = 0, storeBudget = 0;  // its MemoryBytes and budget at the frame's end
};

// Renders like the patched TraceTask: Begin per block, Reuse or trace each sample, End.
// With `shown` (the front end's image, kept from frame to frame), only the pixels End()
// reports changed are copied into it, as the patched trace task sends them.
// `budgetBytes`: the store's memory budget (0: the default).
FcResult RenderFc(const ToyScene &scene, int frame, SceneEffects effects = {}, std::vector<std::string> inexact = {},
                  int threads = 1, Image *shown = nullptr, std::uint64_t budgetBytes = 0) {
    FrameCoherence &fc = FrameCoherence::Get();
    SceneSignature sig = Signature(scene);
    sig.inexactEffects = inexact;
    PublishSceneSignature(kScene, sig);
    FrameSetup setup = ToySetup(frame, threads);
    setup.frontEndKeepsImage = shown != nullptr;
    setup.memoryBudgetBytes = budgetBytes;
    fc.BeginFrame(true, setup, kScene, effects);
    FcResult r;
    r.image.assign(std::size_t(kW) * kH * 5, 0.0f);
    BlockTracer tracer(fc.Plan());
    ToyReplayer replayer(scene);
    ToyShadowReplayer shadowReplayer(scene);
    ToySurfaceReplayer surfaceReplayer(scene);
    if (toyReplays) {
        tracer.SetTieReplayer(&replayer);
        tracer.SetShadowReplayer(&shadowReplayer, toyShadowCachesMatter);
        if (toySurfaceReplays) tracer.SetSurfaceReplayer(&surfaceReplayer);
    }
    std::uint32_t serial = 0;
    for (int by = 0; by < kH; by += kBlock)
        for (int bx = 0; bx < kW; bx += kBlock, ++serial) {
            const int right = bx + kBlock - 1, bottom = by + kBlock - 1;
            if (tracer.Begin(serial, bx, by, right, bottom)) {
                for (int y = by; y <= bottom; ++y)
                    for (int x = bx; x <= right; ++x) tracer.StoredPixel(x, y, &r.image[(std::size_t(y) * kW + x) * 5]);
                continue;
            }
            RenderBlock(bx, by, right, bottom,
                        [&](double x, double y, float c[5]) {
                            if (tracer.Reuse(x, y, c)) return;
                            tracer.BeginSample();
                            TraceToy(scene, x, y, c);
                            tracer.EndSample(x, y, c);
                            ++r.tracedSamples;
                        },
                        r.image);
            for (int y = by; y <= bottom; ++y)
                for (int x = bx; x <= right; ++x) tracer.SetPixel(x, y, &r.image[(std::size_t(y) * kW + x) * 5]);
            tracer.End();
            // The patched trace task sends only the changed pixels when this says so.
            EXPECT_EQ(tracer.SendOnlyChanged(), shown != nullptr);
            int l, t, rr, b;
            if (!tracer.ChangedRect(l, t, rr, b)) continue;
            r.changedPixels += tracer.ChangedCount();
            r.changedRectArea += std::uint64_t(rr - l + 1) * std::uint64_t(b - t + 1);
            if (!shown) continue;
            for (int y = t; y <= b; ++y)
                for (int x = l; x <= rr; ++x)
                    if (tracer.PixelChanged(x, y))
                        std::memcpy(&(*shown)[(std::size_t(y) * kW + x) * 5], &r.image[(std::size_t(y) * kW + x) * 5],
                                    5 * sizeof(float));
        }
    if (const SampleStore *store = fc.Plan().store) {
        r.stored = true;
        r.storeBytes = store->MemoryBytes();
        r.storeBudget = store->BudgetBytes();
    }
    fc.EndFrame(0);
    return r;
}

// Each test starts a run of its own: fc off forgets what an earlier test left.
class FrameCoherenceRun : public ::testing::Test {
  protected:
    void SetUp() override {
        toyReplays = true;
        toySurfaceReplays = true;
        toyShadowCachesMatter = true;
        ToySurfaceReplayer::lies = false;
        toyKeepsShadowTests = true;
        toyCacheHeld = false;
        ToyShadowReplayer::lies = false;
        FrameCoherence &fc = FrameCoherence::Get();
        fc.BeginFrame(false, ToySetup(0), nullptr, {});
        fc.EndFrame(0);
    }
};

ToyScene Frame(double moverX) {
    ToyScene s;
    s.boxes.push_back({1, Box{Vec3{-5, -5, 5}, Vec3{30, 30, 6}}});        // back wall
    s.boxes.push_back({2, Box{Vec3{moverX, 2, 0}, Vec3{moverX + 2.5, 3.5, 1}}});  // a moving box
    s.boxes.push_back({3, Box{Vec3{11, 6, 2}, Vec3{13, 6.5, 3}}});        // still, casts a shadow
    return s;
}

TEST_F(FrameCoherenceRun, EveryFrameEqualsTheFullRenderAndTracesLess) {
    std::uint64_t fullSamples = 0, fcSamples = 0;
    for (int f = 0; f < 12; ++f) {
        const ToyScene scene = Frame(1.0 + 0.75 * f);
        const Image full = RenderFull(scene);
        const FcResult fc = RenderFc(scene, f + 1);
        // Invariant: frame coherence never changes a pixel.
        ASSERT_EQ(std::memcmp(full.data(), fc.image.data(), full.size() * sizeof(float)), 0) << "frame " << f + 1;
        if (f == 0) {
            EXPECT_EQ(FrameCoherence::Get().LastStats().fullReason, "first frame");
            fullSamples = fc.tracedSamples;
        } else {
            EXPECT_EQ(FrameCoherence::Get().LastStats().fullReason, "");
            EXPECT_GT(fc.tracedSamples, 0u);
            fcSamples += fc.tracedSamples;
        }
    }
    // A box a few pixels wide moving: far fewer samples than full frames.
    EXPECT_LT(fcSamples, 11 * fullSamples / 3);
}

TEST_F(FrameCoherenceRun, SamplesFarFromASlowChangeAreClearedWithoutATestAndFramesStayExact) {
    // The box creeps, then jumps across the image, then creeps again: samples its cones
    // reach but that missed it by more than it moves keep being clean without a test
    // (change_drift.h); after the jump they are tested again. Every frame stays exact.
    std::uint64_t tested = 0, cleared = 0;
    for (int f = 0; f < 16; ++f) {
        const double x = f < 8 ? 1.0 + 0.05 * f : 9.0 + 0.05 * f;
        const ToyScene scene = Frame(x);
        const Image full = RenderFull(scene);
        const FcResult fc = RenderFc(scene, f + 1);
        ASSERT_EQ(std::memcmp(full.data(), fc.image.data(), full.size() * sizeof(float)), 0) << "frame " << f + 1;
        const FrameStats &stats = FrameCoherence::Get().LastStats();
        if (f == 8) {
            EXPECT_GT(stats.samplesTested, 0u);  // the jump: tested anew
        }
        tested += stats.samplesTested;
        cleared += stats.samplesCleared;
    }
    EXPECT_GT(tested, 0u);
    EXPECT_GT(cleared, 0u);
}

TEST_F(FrameCoherenceRun, TheChangedPixelsAloneKeepTheFrontEndsImageExact) {
    // The front end keeps its image between frames and is sent only the pixels End() marks
    // changed: it must hold every frame's full render.
    Image shown(std::size_t(kW) * kH * 5, -1.0f);
    std::uint64_t changed = 0, rectArea = 0;
    for (int f = 0; f < 12; ++f) {
        const ToyScene scene = Frame(1.0 + 0.75 * f);
        const FcResult fc = RenderFc(scene, f + 1, {}, {}, 1, &shown);
        ASSERT_EQ(std::memcmp(RenderFull(scene).data(), shown.data(), shown.size() * sizeof(float)), 0)
            << "frame " << f + 1;
        if (f == 0) {
            EXPECT_EQ(fc.changedPixels, std::uint64_t(kW) * kH);  // nothing to compare with
            continue;
        }
        EXPECT_LE(fc.changedPixels, fc.changedRectArea);
        changed += fc.changedPixels;
        rectArea += fc.changedRectArea;
    }
    EXPECT_GT(changed, 0u);
    EXPECT_LE(changed, rectArea);
}

TEST_F(FrameCoherenceRun, UnchangedFrameReusesEveryBlock) {
    RenderFc(Frame(2.0), 1);
    const FcResult again = RenderFc(Frame(2.0), 2);
    EXPECT_EQ(again.tracedSamples, 0u);
    EXPECT_EQ(FrameCoherence::Get().LastStats().traced, 0u);
    EXPECT_EQ(FrameCoherence::Get().LastStats().reused, std::uint64_t(kW * kH));
}

TEST_F(FrameCoherenceRun, LightChangeIsAFullFrameAndTheCameraStartsASequence) {
    RenderFc(Frame(2.0), 1);
    ToyScene lit = Frame(2.0);
    lit.lightY = 40;
    const FcResult full = RenderFc(lit, 2);
    EXPECT_EQ(FrameCoherence::Get().LastStats().fullReason, "light sources changed");
    ASSERT_EQ(std::memcmp(full.image.data(), RenderFull(lit).data(), full.image.size() * sizeof(float)), 0);
    lit.camera = 8;
    RenderFc(lit, 3);
    // Not recorded: the full frame before paused recording (RecordingPolicy).
    EXPECT_EQ(FrameCoherence::Get().LastStats().fullReason, "camera changed: new sequence (recording paused)");
}

TEST_F(FrameCoherenceRun, RecordingPausesWhileFramesStayFullAndResumes) {
    ToyScene s = Frame(2.0);
    RenderFc(s, 1);
    for (int f = 2; f <= 5; ++f) {
        s.camera = 100 + f;  // a moving camera
        RenderFc(s, f);
    }
    // Invariant: after a wasted full frame, the hooks go idle while frames stay full.
    EXPECT_FALSE(FrameCoherence::Get().Active());
    EXPECT_NE(FrameCoherence::Get().LastStats().fullReason.find("recording paused"), std::string::npos);
    // The camera stops: this frame records again, the next reuses.
    RenderFc(s, 6);
    EXPECT_EQ(FrameCoherence::Get().LastStats().fullReason, "recording resumed");
    const FcResult r = RenderFc(s, 7);
    EXPECT_EQ(r.tracedSamples, 0u);
    EXPECT_EQ(std::memcmp(r.image.data(), RenderFull(s).data(), r.image.size() * sizeof(float)), 0);
}

TEST_F(FrameCoherenceRun, ALocalChangeAfterAFullFrameReusesWhatTheFullFrameRecorded) {
    ToyScene s = Frame(2.0);
    RenderFc(s, 1);
    s.lightY = 40;
    const FcResult full = RenderFc(s, 2);
    EXPECT_EQ(FrameCoherence::Get().LastStats().fullReason, "light sources changed");
    // Invariant: the pause a full frame begins keeps that frame's record, so the next frame,
    // whose change is local, follows it instead of recording afresh.
    s.boxes[1].box.lo.x += 0.25;
    s.boxes[1].box.hi.x += 0.25;
    const FcResult next = RenderFc(s, 3);
    EXPECT_EQ(FrameCoherence::Get().LastStats().fullReason, "");
    EXPECT_GT(next.tracedSamples, 0u);
    EXPECT_LT(next.tracedSamples, full.tracedSamples / 2);
    EXPECT_EQ(std::memcmp(next.image.data(), RenderFull(s).data(), next.image.size() * sizeof(float)), 0);
}

TEST_F(FrameCoherenceRun, InexactEffectsReuseOnlyStaticReproducibleFrames) {
    const ToyScene s = Frame(2.0);
    RenderFc(s, 1, {}, {"radiosity"}, 1);
    EXPECT_EQ(RenderFc(s, 2, {}, {"radiosity"}, 1).tracedSamples, 0u);  // one thread: reproducible
    EXPECT_GT(RenderFc(s, 3, {}, {"radiosity"}, 2).tracedSamples, 0u);  // two: render settings changed
    EXPECT_GT(RenderFc(s, 4, {}, {"radiosity"}, 2).tracedSamples, 0u);  // two threads: never reused
    EXPECT_NE(FrameCoherence::Get().LastStats().fullReason.find("radiosity"), std::string::npos);
    RenderFc(s, 5, {}, {"jittered area light"}, 1);
    EXPECT_GT(RenderFc(s, 6, {}, {"jittered area light"}, 1).tracedSamples, 0u);  // frames differ
    // A moved object under an inexact effect: full frame, still exact.
    const FcResult moved = RenderFc(Frame(3.0), 7, {}, {"jittered area light"}, 1);
    EXPECT_EQ(std::memcmp(moved.image.data(), RenderFull(Frame(3.0)).data(), moved.image.size() * sizeof(float)), 0);
}

TEST_F(FrameCoherenceRun, OffForgetsEverything) {
    RenderFc(Frame(2.0), 1);
    FrameCoherence &fc = FrameCoherence::Get();
    PublishSceneSignature(kScene, Signature(Frame(2.0)));
    fc.BeginFrame(false, ToySetup(2), kScene, {});
    EXPECT_FALSE(fc.Active());
    fc.EndFrame(0);
    RenderFc(Frame(2.0), 3);
    EXPECT_EQ(fc.LastStats().fullReason, "first frame");
}

// Ends a block of the tests that drive the tracer by hand: every pixel black (they check
// which samples were traced or reused, not pixels).
void EndBlockInBlack(BlockTracer &tracer) {
    for (int y = 0; y < kBlock; ++y)
        for (int x = 0; x < kBlock; ++x) {
            const float c[5] = {0, 0, 0, 0, 0};
            tracer.SetPixel(x, y, c);
        }
    tracer.End();
}

}  // namespace
}  // namespace povrayfc

namespace povrayfc {
namespace {

// A loose ray that hit nothing (POV-Ray's 2e10 "infinity") is not held by a block's loose
// box; a change it passes through must still make its sample dirty (a regression: it was
// skipped whenever the box missed the change).
TEST_F(FrameCoherenceRun, UnboundedLooseRayNotHeldByTheLooseBoxStillSeesAChange) {
    FrameCoherence &fc = FrameCoherence::Get();
    auto frame = [&](int n, double boxX) {
        ToyScene s;
        s.boxes.push_back({7, Box{Vec3{boxX, 50, 50}, Vec3{boxX + 1, 51, 51}}});
        SceneSignature sig = Signature(s);
        PublishSceneSignature(kScene, sig);
        fc.BeginFrame(true, ToySetup(n), kScene, {});
        BlockTracer tracer(fc.Plan());
        int traced = 0;
        const bool reused = tracer.Begin(0, 0, 0, kBlock - 1, kBlock - 1);
        if (!reused) {
            for (int y = 0; y < kBlock; ++y)
                for (int x = 0; x < kBlock; ++x) {
                    float c[5] = {0, 0, 0, 0, 0};
                    if (tracer.Reuse(x, y, c)) continue;
                    tracer.BeginSample();
                    // Short loose segments far from the box, and from pixel (1, 1) a
                    // reflection-like ray towards (50.5, 50.5, 50.5) that hit nothing.
                    const double o[3] = {double(x), double(y), -3}, d[3] = {0.1, 0.2, 1};
                    RecordRaySegment(o, d, 0.5, kUnitNothing);
                    const double p[3] = {double(x), double(y), 0};
                    const double r[3] = {50.5 - x, 50.5 - y, 50.5};
                    if (x == 1 && y == 1) RecordRaySegment(p, r, 2e10, kUnitNothing);
                    tracer.EndSample(x, y, c);
                    ++traced;
                }
            EndBlockInBlack(tracer);
        }
        fc.EndFrame(0);
        return traced;
    };
    EXPECT_EQ(frame(1, 100), kBlock * kBlock);  // first frame; the box is far away
    EXPECT_EQ(frame(2, 100), 0);                 // nothing changed
    // The box moves into the long ray's way (old place far from everything).
    EXPECT_EQ(frame(3, 50), 1);
}

}  // namespace
}  // namespace povrayfc

namespace povrayfc {
namespace {

// A block left out of a frame (a renderer told to render some blocks only) missed that
// frame's changes: it must be traced again when it is rendered later, not reused.
TEST_F(FrameCoherenceRun, BlockLeftOutOfAFrameIsTracedAgainLater) {
    FrameCoherence &fc = FrameCoherence::Get();
    auto frame = [&](int n, const ToyScene &scene, bool renderSecondBlock) {
        PublishSceneSignature(kScene, Signature(scene));
        fc.BeginFrame(true, ToySetup(n), kScene, {});
        BlockTracer tracer(fc.Plan());
        int traced = 0;
        for (std::uint32_t serial = 0; serial < 2; ++serial) {
            if (serial == 1 && !renderSecondBlock) continue;
            const int left = int(serial) * kBlock;
            if (tracer.Begin(serial, left, 0, left + kBlock - 1, kBlock - 1)) continue;
            for (int y = 0; y < kBlock; ++y)
                for (int x = left; x < left + kBlock; ++x) {
                    float c[5];
                    if (tracer.Reuse(x, y, c)) continue;
                    tracer.BeginSample();
                    TraceToy(scene, x, y, c);
                    tracer.EndSample(x, y, c);
                    tracer.SetPixel(x, y, c);
                    ++traced;
                }
            tracer.End();
        }
        fc.EndFrame(0);
        return traced;
    };
    frame(1, Frame(5.0), true);
    frame(2, Frame(5.5), false);  // the mover crosses block 1, which is not rendered
    // Invariant: block 1's record is gone, so all of it is traced.
    EXPECT_EQ(frame(3, Frame(5.5), true), kBlock * kBlock);
}

}  // namespace
}  // namespace povrayfc

namespace povrayfc {
namespace {

// A change that dirties every sample each frame (the back wall creeps forward): recording
// pauses, and each fruitless try to resume makes the next pause twice as long, also with
// the full frame recording resumes with in between (it used to reset the back-off).
TEST_F(FrameCoherenceRun, BusyFramesPauseLongerEachTime) {
    std::vector<int> pauses;
    int idle = 0;
    for (int f = 1; f <= 40; ++f) {
        ToyScene s = Frame(2.0);
        s.boxes[0].box.lo.z = 5.0 - 0.01 * f;
        const FcResult fc = RenderFc(s, f);
        ASSERT_EQ(std::memcmp(RenderFull(s).data(), fc.image.data(), fc.image.size() * sizeof(float)), 0) << f;
        if (FrameCoherence::Get().LastStats().fullReason.find("(recording paused)") != std::string::npos) {
            ++idle;
        } else if (idle > 0) {
            pauses.push_back(idle);
            idle = 0;
        }
    }
    ASSERT_GE(pauses.size(), 3u);
    EXPECT_EQ(pauses[0], 2);
    EXPECT_EQ(pauses[1], 4);
    EXPECT_EQ(pauses[2], 8);
}

}  // namespace
}  // namespace povrayfc

namespace povrayfc {
namespace {

// A replayed block reuses every clean sample whatever order POV-Ray asks for them in
// (anti-aliasing that supersamples other pixels than last frame asks in another order,
// and for samples never stored): the tracer looks the samples up, not just in turn.
TEST_F(FrameCoherenceRun, ReplayReusesCleanSamplesAskedInAnyOrder) {
    FrameCoherence &fc = FrameCoherence::Get();
    // One sample per pixel; from pixel (0, 0) a ray through the box at x = boxX.
    auto frame = [&](int n, double boxX, bool reversed, int &reused) {
        ToyScene s;
        s.boxes.push_back({7, Box{Vec3{boxX, 0, 10}, Vec3{boxX + 1, 1, 11}}});
        PublishSceneSignature(kScene, Signature(s));
        fc.BeginFrame(true, ToySetup(n), kScene, {});
        BlockTracer tracer(fc.Plan());
        int traced = 0;
        reused = 0;
        if (!tracer.Begin(0, 0, 0, kBlock - 1, kBlock - 1)) {
            for (int k = 0; k < kBlock * kBlock + 1; ++k) {
                const int i = reversed ? kBlock * kBlock - k : k;  // one more: a new sample
                const double x = i % kBlock + (i == kBlock * kBlock ? 0.25 : 0.0), y = i / kBlock % kBlock;
                float c[5] = {0, 0, 0, 0, 0};
                if (tracer.Reuse(x, y, c)) {
                    ++reused;
                    continue;
                }
                tracer.BeginSample();
                const double o[3] = {x, y, -3}, d[3] = {0, 0, 1};
                // Only (0, 0) reaches the box's places: it ends on the box when it is there.
                if (i == 0 && boxX == 0.0)
                    RecordRaySegment(o, d, 13.0, 0);
                else
                    RecordRaySegment(o, d, i == 0 ? 20.0 : 1.0, kUnitNothing);
                tracer.EndSample(x, y, c);
                ++traced;
            }
            EndBlockInBlack(tracer);
        }
        fc.EndFrame(0);
        return traced;
    };
    int reused = 0;
    EXPECT_EQ(frame(1, 0.0, false, reused), kBlock * kBlock + 1);
    // The box moves off the ray of (0, 0): that sample alone is traced, in either order.
    EXPECT_EQ(frame(2, 5.0, true, reused), 1);
    EXPECT_EQ(reused, kBlock * kBlock);
    EXPECT_EQ(frame(3, 0.0, false, reused), 1);
    EXPECT_EQ(reused, kBlock * kBlock);
}

}  // namespace
}  // namespace povrayfc

namespace povrayfc {
namespace {

// A block replayed with its samples in the same order is updated in place: the record is
// the same object, a traced sample's packed segments overwrite its old ones when they take
// no more bytes and go to the end otherwise, the record is compacted once a quarter is dead, and the
// updated samples are still found by later changes.
TEST_F(FrameCoherenceRun, ReplayedBlockInTheSameOrderIsUpdatedInPlace) {
    FrameCoherence &fc = FrameCoherence::Get();
    const int n = kBlock * kBlock;
    // Sample 0's ray reaches x = 0 at z = 10..11 and is recorded as `pieces` segments; the
    // others end before z = 10. The box sits on that ray at x = 0 (where it ends), or off it.
    auto frame = [&](int number, bool boxOnRay, bool reversed, int pieces) {
        ToyScene s;
        const double boxX = boxOnRay ? 0.0 : 5.0;
        s.boxes.push_back({7, Box{Vec3{boxX - 0.5, -0.5, 10}, Vec3{boxX + 0.5, 0.5, 11}}});
        PublishSceneSignature(kScene, Signature(s));
        fc.BeginFrame(true, ToySetup(number), kScene, {});
        BlockTracer tracer(fc.Plan());
        int traced = 0;
        if (!tracer.Begin(0, 0, 0, kBlock - 1, kBlock - 1)) {
            for (int k = 0; k < n; ++k) {
                const int i = reversed ? n - 1 - k : k;
                const double x = i % kBlock, y = i / kBlock;
                float c[5] = {0, 0, 0, 0, 0};
                if (tracer.Reuse(x, y, c)) continue;
                tracer.BeginSample();
                if (i == 0) {
                    // In pieces (like a ray through transparent objects), the last ending on
                    // the box when it is on the ray.
                    const double reach = boxOnRay ? 13.0 : 20.0;
                    for (int p = 0; p < pieces; ++p) {
                        const double o[3] = {x, y, -3.0 + reach * p / pieces}, d[3] = {0, 0, 1};
                        RecordRaySegment(o, d, reach / pieces, (boxOnRay && p == pieces - 1) ? 0 : kUnitNothing);
                    }
                } else {
                    const double o[3] = {x, y, -3}, d[3] = {0, 0, 1};
                    RecordRaySegment(o, d, 1.0, kUnitNothing);
                }
                tracer.EndSample(x, y, c);
                ++traced;
            }
            EndBlockInBlack(tracer);
        }
        fc.EndFrame(0);
        return traced;
    };
    auto record = [&] { return fc.Plan().store->Find(0); };
    // Every sample's packed segments lie inside the record, no byte shared, and the dead
    // bytes are counted: live + dead = all, and at most a quarter dead.
    auto consistent = [&](const BlockRecord &r) {
        std::size_t live = 0;
        std::vector<int> owner(r.packed.size(), 0);
        for (const StoredSample &smp : r.samples) {
            if (smp.segmentCount == StoredSample::kEverything) continue;
            if (smp.firstByte > r.packed.size()) return false;
            const std::size_t size = PackedSize(r.packed.data() + smp.firstByte, smp.segmentCount);
            if (std::size_t(smp.firstByte) + size > r.packed.size()) return false;
            for (std::size_t k = 0; k < size; ++k)
                if (owner[smp.firstByte + k]++) return false;
            live += size;
        }
        return live + r.deadBytes == r.packed.size() && 4 * r.deadBytes <= r.packed.size();
    };

    ASSERT_EQ(frame(1, true, false, 1), n);
    const BlockRecord *first = record();
    ASSERT_NE(first, nullptr);
    // The box moves off sample 0's ray: it alone is traced, in place, its one segment
    // overwritten by one (which, ending on nothing now, takes the 4 bytes of a unit less:
    // a store this small writes segments in full, SampleStore::PackTightly).
    const std::uint32_t at = first->samples[0].firstByte;
    EXPECT_EQ(frame(2, false, false, 1), 1);
    EXPECT_EQ(record(), first);
    EXPECT_EQ(record()->samples[0].firstByte, at);
    EXPECT_EQ(record()->deadBytes, 4u);
    EXPECT_TRUE(consistent(*record()));
    // Back onto the ray, now recorded as three segments: found dirty, traced, appended.
    EXPECT_EQ(frame(3, true, false, 3), 1);
    EXPECT_EQ(record(), first);
    EXPECT_EQ(record()->samples[0].segmentCount, 3u);
    EXPECT_TRUE(consistent(*record()));
    // Many more frames, the piece count changing every time: always found, always in place,
    // compacted once a quarter is dead. The cones grow by each frame's new segments until
    // twice as many as the record holds were added since they were built; then they are
    // dropped, to be built afresh by the next frame that tests the block.
    int dropped = 0;
    for (int f = 4; f < 40; ++f) {
        const bool builtBefore = record()->fansBuilt;
        const std::size_t grownBefore = record()->grownSegments;
        const int pieces = 1 + f % 4;
        EXPECT_EQ(frame(f, f % 2 == 1, false, pieces), 1) << "frame " << f;
        EXPECT_EQ(record(), first) << "frame " << f;
        EXPECT_TRUE(consistent(*record())) << "frame " << f;
        std::size_t live = 0;
        for (const StoredSample &smp : record()->samples) live += smp.segmentCount;
        if (record()->fansBuilt) {
            EXPECT_EQ(record()->grownSegments, (builtBefore ? grownBefore : 0) + std::size_t(pieces)) << "frame " << f;
            EXPECT_LE(record()->grownSegments, 2 * live) << "frame " << f;
        } else {
            EXPECT_GT((builtBefore ? grownBefore : 0) + std::size_t(pieces), 2 * live) << "frame " << f;
            EXPECT_EQ(record()->grownSegments, 0u) << "frame " << f;
            ++dropped;
        }
    }
    EXPECT_GE(dropped, 1);
    // Asked in another order the block gets a new record, as before.
    EXPECT_EQ(frame(40, false, true, 1), 1);
    EXPECT_NE(record(), first);
    EXPECT_TRUE(consistent(*record()));
    EXPECT_EQ(record()->deadBytes, 0u);
}

}  // namespace
}  // namespace povrayfc

namespace povrayfc {
namespace {

// Two boxes with the same corners and other colours (ids): the toy shows the first in
// scene order, as POV-Ray shows the first its bounding tree meets.
ToyScene Coincident(bool redFirst, double moverX) {
    ToyScene s = Frame(moverX);
    const ToyBox red{4, Box{Vec3{1, 5, 2}, Vec3{5, 7, 3}}}, blue{5, Box{Vec3{1, 5, 2}, Vec3{5, 7, 3}}};
    s.boxes.push_back(redFirst ? red : blue);
    s.boxes.push_back(redFirst ? blue : red);
    return s;
}

TEST_F(FrameCoherenceRun, SwappedCoincidentObjectsAreTracedAgain) {
    // Invariant: the same objects in another order are a change for the samples whose
    // nearest hit was a tie, and for them alone: run again, their tied searches find the
    // other box.
    const ToyScene first = Coincident(true, 0), second = Coincident(false, 0);
    RenderFc(first, 1);
    const FcResult r = RenderFc(second, 2);
    EXPECT_EQ(r.image, RenderFull(second));
    EXPECT_GT(r.tracedSamples, 0u);
    EXPECT_LT(r.tracedSamples, 60u);  // the tied box's samples (8 pixels, their AA borders)
    EXPECT_GT(FrameCoherence::Get().LastStats().tiedSamplesReplayed, 0u);
}

TEST_F(FrameCoherenceRun, TiedSamplesAreKeptWhenTheirSearchesFindTheSameAfterAFarChange) {
    // A change far from the tie may reshape POV-Ray's bounding tree. The tied samples'
    // searches are run again: here the same box still wins, so they are kept. A frame
    // where nothing moved keeps them without a search.
    RenderFc(Coincident(true, 0), 1);
    const FcResult still = RenderFc(Coincident(true, 0), 2);
    EXPECT_EQ(still.tracedSamples, 0u);
    EXPECT_EQ(FrameCoherence::Get().LastStats().tiedSamplesReplayed, 0u);
    const ToyScene moved = Coincident(true, 0.5);
    const FcResult r = RenderFc(moved, 3);
    EXPECT_EQ(r.image, RenderFull(moved));
    const FrameStats stats = FrameCoherence::Get().LastStats();
    EXPECT_GT(stats.tiedSamplesKept, 0u);
    EXPECT_LE(stats.tiedSamplesKept, stats.tiedSamplesReplayed);
    // Without a replayer (or for a search that cannot be run again) they are traced again.
    const FcResult unreplayed = [&] {
        SetUp();
        toyReplays = false;
        RenderFc(Coincident(true, 0), 1);
        return RenderFc(moved, 2);
    }();
    EXPECT_EQ(unreplayed.image, r.image);
    EXPECT_EQ(FrameCoherence::Get().LastStats().tiedSamplesKept, 0u);
    EXPECT_GE(unreplayed.tracedSamples, r.tracedSamples + stats.tiedSamplesKept);
}

}  // namespace
}  // namespace povrayfc

namespace povrayfc {
namespace {

// Units by hand: `hashes` and `geometries` per unit, each a unit box at x = 10 * i.
SceneSignature UnitsScene(const std::vector<std::uint64_t> &hashes, const std::vector<std::uint64_t> &geometries,
                          const std::vector<double> &xs) {
    SceneSignature s;
    for (std::size_t i = 0; i < hashes.size(); ++i) {
        UnitSignature u;
        u.hash = hashes[i];
        u.geometry = geometries[i];
        u.bounds = Box{Vec3{xs[i], 0, 5}, Vec3{xs[i] + 1, 4, 6}};
        s.units.push_back(u);
        ObjectSignature o;
        o.hash = hashes[i];
        s.objects.push_back(o);
    }
    s.complete = true;
    return s;
}

// One 4x4 block, one sample per pixel, each a ray along +z from (x, y, 0) that ends on
// unit `endsOn(x, y)` at z = 5 (or goes on to z = 20 with kUnitNothing). Returns how many
// samples were traced.
template <class EndsOn>
int RenderUnitsBlock(int frame, const SceneSignature &sig, EndsOn endsOn) {
    FrameCoherence &fc = FrameCoherence::Get();
    PublishSceneSignature(kScene, sig);
    fc.BeginFrame(true, ToySetup(frame), kScene, {});
    BlockTracer tracer(fc.Plan());
    int traced = 0;
    if (!tracer.Begin(0, 0, 0, kBlock - 1, kBlock - 1)) {
        for (int y = 0; y < kBlock; ++y)
            for (int x = 0; x < kBlock; ++x) {
                float c[5] = {0, 0, 0, 0, 0};
                if (tracer.Reuse(x, y, c)) continue;
                tracer.BeginSample();
                const double o[3] = {double(x), double(y), 0}, d[3] = {0, 0, 1};
                const std::uint32_t unit = endsOn(x, y);
                RecordRaySegment(o, d, unit == kUnitNothing ? 20.0 : 5.0, unit);
                tracer.EndSample(x, y, c);
                ++traced;
            }
        EndBlockInBlack(tracer);
    }
    fc.EndFrame(0);
    return traced;
}

TEST_F(FrameCoherenceRun, AChangedUnitDirtiesExactlyTheSamplesThatEndedOnIt) {
    // Columns 0-1 end on unit 0, 2-3 on unit 1 (both far from every ray's path otherwise).
    auto endsOn = [](int x, int) { return std::uint32_t(x < 2 ? 0 : 1); };
    const std::vector<double> xs = {100, 200};
    EXPECT_EQ(RenderUnitsBlock(1, UnitsScene({1, 2}, {11, 12}, xs), endsOn), 16);
    EXPECT_EQ(RenderUnitsBlock(2, UnitsScene({1, 2}, {11, 12}, xs), endsOn), 0);
    // Invariant: unit 0 changes colour (same geometry): its 8 samples, no other.
    EXPECT_EQ(RenderUnitsBlock(3, UnitsScene({3, 2}, {11, 12}, xs), endsOn), 8);
    // ... and again (its id is kept across frames only while it is unchanged).
    EXPECT_EQ(RenderUnitsBlock(4, UnitsScene({4, 2}, {11, 12}, xs), endsOn), 8);
    // Unit 1 changes shape far from every ray: what ended on it, no other.
    EXPECT_EQ(RenderUnitsBlock(5, UnitsScene({4, 5}, {11, 15}, {100, 300}), endsOn), 8);
    EXPECT_EQ(RenderUnitsBlock(6, UnitsScene({4, 5}, {11, 15}, {100, 300}), endsOn), 0);
}

TEST_F(FrameCoherenceRun, AMovedUnitIsMetAtItsNewPlaceNotAtItsOld) {
    // Row 0 ends on unit 0 (at x = 0..1 on the rays' way); the rest go on to z = 20.
    auto endsOn = [](int, int y) { return y == 0 ? 0u : kUnitNothing; };
    const std::vector<std::uint64_t> geometry = {11, 12};
    EXPECT_EQ(RenderUnitsBlock(1, UnitsScene({1, 2}, geometry, {0, 100}), endsOn), 16);
    // Unit 1 moves from far away into the rays of columns 2 and 3 (x = 2..3): the rows that
    // did not end on anything meet its new place (3 rows x 2 columns); row 0 stops before.
    auto endsOnAfter = [](int x, int y) { return y == 0 ? 0u : (x >= 2 ? 1u : kUnitNothing); };
    EXPECT_EQ(RenderUnitsBlock(2, UnitsScene({1, 3}, {11, 13}, {0, 2}), endsOnAfter), 6 + 2);
    // It moves away again: only the samples that ended on it are traced.
    EXPECT_EQ(RenderUnitsBlock(3, UnitsScene({1, 4}, {11, 14}, {0, 300}), endsOn), 6);
}

}  // namespace
}  // namespace povrayfc

namespace povrayfc {
namespace {

// How the shadow tests of RenderShadowedBlock end.
enum class ShadowWay {
    kPane,          // they pass unit 0, a glass pane, at 10 and reach the light
    kBlocked,       // unit 0's opaque surface answers them at 10
    kPaneThenBlocked,  // they pass unit 2 at 4 and the loop goes on from there, as POV-Ray's
                       // shadow loop does, to unit 0's opaque surface at 10
};

// One 4x4 block: each sample a camera ray from (x, y, 0) ending on unit 1 at z = 5 and, from
// there, a shadow test up +y over 50 that ends the `way` says.
int RenderShadowedBlock(int frame, const SceneSignature &sig, ShadowWay way) {
    FrameCoherence &fc = FrameCoherence::Get();
    PublishSceneSignature(kScene, sig);
    fc.BeginFrame(true, ToySetup(frame), kScene, {});
    BlockTracer tracer(fc.Plan());
    int traced = 0;
    if (!tracer.Begin(0, 0, 0, kBlock - 1, kBlock - 1)) {
        for (int y = 0; y < kBlock; ++y)
            for (int x = 0; x < kBlock; ++x) {
                float c[5] = {0, 0, 0, 0, 0};
                if (tracer.Reuse(x, y, c)) continue;
                tracer.BeginSample();
                const double o[3] = {double(x), double(y), 0}, d[3] = {0, 0, 1};
                RecordRaySegment(o, d, 5.0, 1);
                {
                    double p[3] = {double(x), double(y), 5}, depth = 50.0;
                    const double up[3] = {0, 1, 0};
                    ShadowSegmentRecord shadow(p, up, depth);  // recorded when it goes
                    double blocker = 10.0;
                    if (way == ShadowWay::kPaneThenBlocked) {
                        shadow.PassedAt(4.0, 2);
                        depth -= 4.0;
                        p[1] += 4.0;
                        blocker -= 4.0;
                    }
                    if (way == ShadowWay::kPane)
                        shadow.PassedAt(10.0, 0);
                    else
                        shadow.BlockedAt(blocker, 0, true);
                }
                tracer.EndSample(x, y, c);
                ++traced;
            }
        EndBlockInBlack(tracer);
    }
    fc.EndFrame(0);
    return traced;
}

SceneSignature BlockerScene(std::uint64_t blockerHash, bool blockerOpaque) {
    SceneSignature s = UnitsScene({blockerHash, 2}, {11, 12}, {0, 100});
    s.units[0].opaque = blockerOpaque;
    return s;
}

// Unit 0 an opaque ball (centre x, y, z = 5, radius 5) on the shadow tests' way up from
// z = 5, or no ball at all.
SceneSignature BallScene(std::uint64_t hash, double x, double y, bool ball) {
    SceneSignature s = UnitsScene({1000 + hash, 2}, {2000 + hash, 12}, {0, 100});
    s.units[0].bounds = Box{Vec3{x - 5, y - 5, 0}, Vec3{x + 5, y + 5, 10}};
    s.units[0].opaque = ball;
    s.units[0].hasBall = ball;
    s.units[0].ball = Ball{Vec3{x, y, 5}, 5};
    return s;
}

TEST_F(FrameCoherenceRun, AMovedOpaqueBallKeepsTheShadowsItStillCasts) {
    // Invariant: a shadow test an opaque surface darkened stays dark while an opaque ball of
    // the new frame crosses its whole way; the shadow tests run up from y = 0..3 over 50.
    EXPECT_EQ(RenderShadowedBlock(1, BallScene(1, 1.5, 20, true), ShadowWay::kBlocked), 16);
    EXPECT_EQ(RenderShadowedBlock(2, BallScene(2, 1.5, 23, true), ShadowWay::kBlocked), 0);   // moved along the way
    EXPECT_EQ(RenderShadowedBlock(3, BallScene(3, 4.0, 23, true), ShadowWay::kBlocked), 0);   // and aside, still across
    EXPECT_EQ(RenderShadowedBlock(4, BallScene(4, 9.0, 23, true), ShadowWay::kBlocked), 16);  // off their way
    EXPECT_EQ(RenderShadowedBlock(5, BallScene(5, 1.5, 20, true), ShadowWay::kBlocked), 0);
    EXPECT_EQ(RenderShadowedBlock(6, BallScene(6, 1.5, 52, true), ShadowWay::kBlocked), 16);  // past the light
    EXPECT_EQ(RenderShadowedBlock(7, BallScene(7, 1.5, 20, true), ShadowWay::kBlocked), 0);
    EXPECT_EQ(RenderShadowedBlock(8, BallScene(8, 1.5, 22, false), ShadowWay::kBlocked), 16); // no longer opaque
}

// Units: 0 the opaque blocker, 1 what the camera rays end on, 2 a glass pane under the
// blocker, and maybe 3, a newcomer whose box is `newcomer`.
SceneSignature BlockedShadowScene(std::uint64_t glassGeometry, const Box &glass, bool newcomerTranslucent,
                                  const Box *newcomer) {
    SceneSignature s = UnitsScene({1, 2, 100 + glassGeometry}, {11, 12, glassGeometry}, {0, 100, 0});
    s.units[0].bounds = Box{Vec3{-1, 9, 4}, Vec3{5, 14, 6}};
    s.units[0].opaque = true;
    s.units[2].bounds = glass;
    s.units[2].translucent = true;
    if (newcomer != nullptr) {
        UnitSignature u;
        u.hash = u.geometry = 7000 + std::uint64_t(newcomerTranslucent);
        u.bounds = *newcomer;
        u.opaque = !newcomerTranslucent;
        u.translucent = newcomerTranslucent;
        s.units.push_back(u);
        ObjectSignature o;
        o.hash = u.hash;
        s.objects.push_back(o);
    }
    return s;
}

TEST_F(FrameCoherenceRun, AShadowTestPastGlassToAnOpaqueBlockerDependsOnTheGlass) {
    // Invariant: where POV-Ray's loop meets the blocker from depends on the glass it went on
    // from, so a glass that moves dirties the tests that passed it, even when its new place is
    // off their way.
    const Box glass{Vec3{-1, 3, 4}, Vec3{5, 4.5, 6}}, away{Vec3{-1, 3, 40}, Vec3{5, 4.5, 42}};
    EXPECT_EQ(RenderShadowedBlock(1, BlockedShadowScene(21, glass, false, nullptr), ShadowWay::kPaneThenBlocked), 16);
    EXPECT_EQ(RenderShadowedBlock(2, BlockedShadowScene(21, glass, false, nullptr), ShadowWay::kPaneThenBlocked), 0);
    EXPECT_EQ(RenderShadowedBlock(3, BlockedShadowScene(22, away, false, nullptr), ShadowWay::kPaneThenBlocked), 16);
}

TEST_F(FrameCoherenceRun, AnOpaqueBlockersTestMeetsWhatLetsLightThroughNotWhatIsOpaque) {
    // Invariant: the loop goes on past a surface that lets light through from a new origin,
    // so a test an opaque surface answered is dirty where such a newcomer crosses its way;
    // an opaque newcomer there darkens it as well, and one off its way changes nothing.
    const Box glass{Vec3{-1, 3, 40}, Vec3{5, 4.5, 42}};  // off every test's way
    const Box across{Vec3{-1, 6, 4}, Vec3{5, 7, 6}}, aside{Vec3{20, 6, 4}, Vec3{21, 7, 6}};
    EXPECT_EQ(RenderShadowedBlock(1, BlockedShadowScene(21, glass, false, nullptr), ShadowWay::kBlocked), 16);
    EXPECT_EQ(RenderShadowedBlock(2, BlockedShadowScene(21, glass, true, &across), ShadowWay::kBlocked), 16);
    SetUp();
    EXPECT_EQ(RenderShadowedBlock(1, BlockedShadowScene(21, glass, false, nullptr), ShadowWay::kBlocked), 16);
    EXPECT_EQ(RenderShadowedBlock(2, BlockedShadowScene(21, glass, false, &across), ShadowWay::kBlocked), 0);
    SetUp();
    EXPECT_EQ(RenderShadowedBlock(1, BlockedShadowScene(21, glass, false, nullptr), ShadowWay::kBlocked), 16);
    EXPECT_EQ(RenderShadowedBlock(2, BlockedShadowScene(21, glass, true, &aside), ShadowWay::kBlocked), 0);
}

TEST_F(FrameCoherenceRun, ARecolouredOpaqueBlockerKeepsItsShadowsAndAGlassPaneDoesNot) {
    // Invariant: a shadow test an opaque surface answered is dark whatever its colour; one
    // that passed a transparent surface carries its colour.
    EXPECT_EQ(RenderShadowedBlock(1, BlockerScene(1, true), ShadowWay::kBlocked), 16);
    EXPECT_EQ(RenderShadowedBlock(2, BlockerScene(3, true), ShadowWay::kBlocked), 0);   // recoloured, still opaque
    EXPECT_EQ(RenderShadowedBlock(3, BlockerScene(4, false), ShadowWay::kBlocked), 16); // now it lets light through
    SetUp();
    EXPECT_EQ(RenderShadowedBlock(1, BlockerScene(1, true), ShadowWay::kPane), 16);
    EXPECT_EQ(RenderShadowedBlock(2, BlockerScene(3, true), ShadowWay::kPane), 16);  // the light passed it
}

}  // namespace
}  // namespace povrayfc

namespace povrayfc {
namespace {

TEST_F(FrameCoherenceRun, AStoreOverItsBudgetTracesTheBlocksLeftOutAndStaysExact) {
    // Invariant: the store never holds more than its budget; the blocks it leaves out are
    // traced in full, and every frame still equals its full render.
    FrameCoherence &fc = FrameCoherence::Get();
    std::size_t budget = 0;
    for (int frame = 1; frame <= 6; ++frame) {
        const ToyScene scene = Frame(0.4 * frame);
        // 20000 bytes: most of the eight blocks' records, not all.
        const FcResult r = RenderFc(scene, frame, {}, {}, 1, nullptr, 20000);
        ASSERT_TRUE(r.stored) << "frame " << frame;  // recording pays: never paused
        budget = r.storeBudget;
        EXPECT_LE(r.storeBytes, budget) << "frame " << frame;
        EXPECT_EQ(r.image, RenderFull(scene)) << "frame " << frame;
        EXPECT_GT(fc.LastStats().overBudgetBlocks, 0u) << "frame " << frame;
        if (frame > 1) {
            EXPECT_LT(fc.LastStats().traced, fc.LastStats().pixels) << "frame " << frame;
        }
    }
    EXPECT_EQ(budget, 20000u);
}

}  // namespace
}  // namespace povrayfc

namespace povrayfc {
namespace {

// The toy scene under a slab of glass at x = [glassX, glassX + 6], high above: the shadow
// tests of the samples below it pass its two surfaces. `glassId` says its tint.
ToyScene UnderGlass(double glassX, double moverX, std::uint64_t glassId = 20, float tint = 0.5f) {
    ToyScene s = Frame(moverX);
    s.boxes.push_back({glassId, Box{Vec3{glassX, 20, -20}, Vec3{glassX + 6, 21, 20}}, tint});
    s.glassShadows = true;
    return s;
}

// The same without the glass.
ToyScene GlassGone(double moverX) {
    ToyScene s = Frame(moverX);
    s.glassShadows = true;
    return s;
}

// Renders `scenes` in turn with fc, each checked against its full render; returns the last
// frame's result.
FcResult RenderAllExact(const std::vector<ToyScene> &scenes) {
    FcResult r;
    for (std::size_t f = 0; f < scenes.size(); ++f) {
        r = RenderFc(scenes[f], int(f) + 1);
        EXPECT_EQ(r.image, RenderFull(scenes[f])) << "frame " << f + 1;
    }
    return r;
}

TEST_F(FrameCoherenceRun, ShadowTestsThroughMovedGlassThatGiveTheSameColourAreKept) {
    // Invariant: a sample whose only rays that meet a change are shadow tests through glass
    // is kept when the tests, run again, give the light the same colour; its pixels are
    // then exactly the full render's. Here the glass slides by one pixel: only the samples
    // at its two edges change colour.
    const std::vector<ToyScene> frames = {UnderGlass(2, 20), UnderGlass(3, 20)};
    ToyShadowReplayer::runs = 0;
    const FcResult kept = RenderAllExact(frames);
    const FrameStats stats = FrameCoherence::Get().LastStats();
    EXPECT_GT(stats.shadowSamplesKept, 0u);
    EXPECT_LE(stats.shadowSamplesKept, stats.replaySamplesTried);
    EXPECT_GT(ToyShadowReplayer::runs, 0);
    // Without replayers every sample under the glass is traced again.
    SetUp();
    toyReplays = false;
    const FcResult traced = RenderAllExact(frames);
    EXPECT_EQ(traced.image, kept.image);
    EXPECT_EQ(FrameCoherence::Get().LastStats().shadowSamplesKept, 0u);
    EXPECT_GE(traced.tracedSamples, kept.tracedSamples + stats.shadowSamplesKept);
}

TEST_F(FrameCoherenceRun, ShadowTestsAreTracedAgainWhenTheRunGivesAnotherColour) {
    // The glass stays and takes another tint: every test gives another colour, so every
    // sample under it is traced (the full render's pixels say so: a replayer that answered
    // the colour kept would leave the old tint).
    const std::vector<ToyScene> frames = {UnderGlass(2, 20, 20, 0.5f), UnderGlass(2, 20, 21, 0.75f)};
    RenderAllExact(frames);
    EXPECT_EQ(FrameCoherence::Get().LastStats().shadowSamplesKept, 0u);
    EXPECT_GT(FrameCoherence::Get().LastStats().replaySamplesTried, 0u);
    SetUp();
    ToyShadowReplayer::lies = true;
    RenderFc(frames[0], 1);
    const FcResult blind = RenderFc(frames[1], 2);
    EXPECT_NE(blind.image, RenderFull(frames[1]));
}

TEST_F(FrameCoherenceRun, ASampleWhoseOtherRaysMeetAChangeIsTracedWhateverItsShadowTestsGive) {
    // The glass moves and so does the box the camera sees under it: the samples whose
    // camera ray the box left or came to change, though their shadow tests, run again from
    // where they started before, give the same colour: the rest of the sample decides.
    RenderAllExact({UnderGlass(0, 1), UnderGlass(1, 2.5), UnderGlass(2, 4)});
    EXPECT_GT(FrameCoherence::Get().LastStats().shadowSamplesKept, 0u);
}

TEST_F(FrameCoherenceRun, ASampleKeptByItsShadowTestsRunsThemAgainWhenTheGlassMovesAway) {
    // Kept in the second frame, the samples under the glass still hold the pieces of the
    // first, which name the glass's first id: when the glass then leaves, every one of them
    // runs its tests again and is traced.
    RenderAllExact({UnderGlass(2, 20), UnderGlass(3, 20), UnderGlass(40, 20)});
    const FrameStats stats = FrameCoherence::Get().LastStats();
    EXPECT_GT(stats.replaySamplesTried, 0u);
    EXPECT_EQ(stats.shadowSamplesKept, 0u);
}

TEST_F(FrameCoherenceRun, ASampleKeptByItsShadowTestsIsTracedWhenTheGlassVanishes) {
    // The glass goes altogether: nothing new appears (no hull), and the blocks under it hold
    // no sample that names its id now, only the stale pieces that name its first one.
    RenderAllExact({UnderGlass(2, 20), UnderGlass(3, 20), GlassGone(20)});
    EXPECT_GT(FrameCoherence::Get().LastStats().replaySamplesTried, 0u);
}

TEST_F(FrameCoherenceRun, AShadowTestThatStartedWithACachedBlockerIsNotKept) {
    // A test that found the shadow caches holding an object is not kept to be run again
    // (the cache decided what it met first): its sample is traced like one without them.
    toyCacheHeld = true;
    RenderAllExact({UnderGlass(2, 20), UnderGlass(3, 20)});
    EXPECT_EQ(FrameCoherence::Get().LastStats().replaySamplesTried, 0u);
    SetUp();
    toyKeepsShadowTests = false;
    RenderAllExact({UnderGlass(2, 20), UnderGlass(3, 20)});
    EXPECT_EQ(FrameCoherence::Get().LastStats().replaySamplesTried, 0u);
}

}  // namespace
}  // namespace povrayfc

namespace povrayfc {
namespace {

// The toy scene with its second box `width` wide from x = 1, growing along its front face
// (which stays at z = 0) with colour `id`, and a blocker above that face's front at x =
// blockerX (its shadow falls on the face when it is over it). Shadow tests are the loop
// (ShadowSegmentRecord), from just in front of the surface hit.
ToyScene Growing(double width, std::uint64_t id = 2, double blockerX = 40, double blockerWidth = 1) {
    ToyScene s = Frame(1);
    s.boxes[1].box.hi.x = 1 + width;
    s.boxes[1].id = id;
    s.boxes.push_back({9, Box{Vec3{blockerX, 6, -0.5}, Vec3{blockerX + blockerWidth, 6.5, 0.5}}});
    s.glassShadows = true;
    return s;
}

TEST_F(FrameCoherenceRun, SurfaceHitsThatFindTheSameSurfaceKeepTheirSamples) {
    // Invariant: a sample whose only rays that meet a change are hits (and the shadow tests
    // that light them) is kept when its camera search, run again, finds the same surface
    // to the bit; its pixels are then exactly the full render's. The box grows along its
    // face: from the third frame (the second traced those samples and kept their hits), its
    // old face is kept, only its new strip traced.
    const std::vector<ToyScene> frames = {Growing(2.5), Growing(3.5), Growing(4.5), Growing(5.5)};
    ToySurfaceReplayer::runs = 0;
    const FcResult kept = RenderAllExact(frames);
    const FrameStats stats = FrameCoherence::Get().LastStats();
    EXPECT_GT(stats.surfaceSamplesKept + stats.shadowSamplesKept, 0u);
    EXPECT_GT(ToySurfaceReplayer::runs, 0);
    SetUp();
    toySurfaceReplays = false;
    const FcResult traced = RenderAllExact(frames);
    EXPECT_EQ(traced.image, kept.image);
    EXPECT_GT(traced.tracedSamples, kept.tracedSamples);
}

TEST_F(FrameCoherenceRun, ASurfaceHitThatFindsAnotherSurfaceIsTraced) {
    // The box grows and takes another colour: every hit on it finds another surface, so its
    // samples are traced (a replayer that answered the signature kept would leave the old
    // colour).
    const std::vector<ToyScene> frames = {Growing(2.5), Growing(3.5), Growing(4.5, 5)};
    RenderAllExact(frames);
    EXPECT_GT(FrameCoherence::Get().LastStats().replaySamplesTried, 0u);
    SetUp();
    ToySurfaceReplayer::lies = true;
    RenderFc(frames[0], 1);
    RenderFc(frames[1], 2);
    const FcResult blind = RenderFc(frames[2], 3);
    EXPECT_NE(blind.image, RenderFull(frames[2]));
}

TEST_F(FrameCoherenceRun, ASampleKeptByItsHitsNamesTheUnitItHitsNow) {
    // Kept in the third frame, the samples on the box name the box's id of that frame (it
    // changed, so it got a new one): when only its colour changes next (no hull, only the
    // segments that ended on it), every one of them is traced.
    RenderAllExact({Growing(2.5), Growing(3.5), Growing(4.5), Growing(4.5, 5)});
    EXPECT_GT(FrameCoherence::Get().LastStats().traced, 0u);
}

// Growing with a slab of glass high above the face, tinted `tint` (its id says so).
ToyScene GrowingUnderGlass(double width, std::uint64_t glassId, float tint) {
    ToyScene s = Growing(width);
    s.boxes.push_back({glassId, Box{Vec3{0, 20, -20}, Vec3{10, 21, 20}}, tint});
    return s;
}

TEST_F(FrameCoherenceRun, AShadowTestThatPassesSomethingNewIsRunAgainWhenThatChanges) {
    // A clear glass (it lets all light through) appears over the growing face: the face's
    // shadow tests, run again, give the same colour though they now pass it, so their one
    // piece to the light is not the new frame's (which would end on the glass). When the
    // glass then takes a tint (its appearance alone: no hull, only segments that ended on
    // it), those samples must run their tests again.
    RenderAllExact({Growing(2.5), Growing(3.5), GrowingUnderGlass(4.5, 30, 1.0f), GrowingUnderGlass(4.5, 31, 0.5f)});
}

TEST_F(FrameCoherenceRun, AShadowTestAnOpaqueBoxAnsweredIsKeptWhileABoxStillAnswersIt) {
    // Where the shadow caches hold only opaque surfaces, a sample traced again keeps the
    // tests an opaque box answered too: the blocker above the face grows, and the samples
    // in its old shadow, run again, are still dark. Their piece then names the blocker's new
    // id: when the blocker goes (nothing new appears; only what ended on its id knows), they
    // are traced and lit.
    toyShadowCachesMatter = false;
    const std::vector<ToyScene> frames = {Growing(4.5, 2, 2, 1), Growing(4.5, 2, 2, 1.5), Growing(4.5, 2, 2, 2),
                                          Growing(4.5, 2, 40, 1)};
    std::uint64_t kept = 0;
    for (std::size_t f = 0; f < frames.size(); ++f) {
        const FcResult r = RenderFc(frames[f], int(f) + 1);
        EXPECT_EQ(r.image, RenderFull(frames[f])) << "frame " << f + 1;
        if (f == 2) kept = FrameCoherence::Get().LastStats().shadowSamplesKept;
    }
    EXPECT_GT(kept, 0u);
    // Where a filtering object may be cached, they are not kept.
    SetUp();
    RenderAllExact({frames[0], frames[1], frames[2]});
    EXPECT_EQ(FrameCoherence::Get().LastStats().shadowSamplesKept, 0u);
}

TEST_F(FrameCoherenceRun, AShadowTestThatWouldLeaveABlockerCachedIsNotKeptWhereCachesMatter) {
    // Under the glass, a roof: the tests pass the glass and end dark. The roof comes down
    // below the glass: run again, each test ends dark as before, but on the roof first,
    // which POV-Ray would cache (the sample's next test would try it first): where the
    // caches may hold a filtering object, none is kept.
    auto roofed = [](double roofY) {
        ToyScene s = UnderGlass(2, 20);
        s.boxes.push_back({40, Box{Vec3{0, roofY, -20}, Vec3{10, roofY + 1, 20}}});
        return s;
    };
    RenderAllExact({roofed(30), roofed(15)});
    EXPECT_GT(FrameCoherence::Get().LastStats().replaySamplesTried, 0u);
    EXPECT_EQ(FrameCoherence::Get().LastStats().shadowSamplesKept, 0u);
}

TEST_F(FrameCoherenceRun, ASampleWhoseShadowTestMeetsAChangeIsTracedWhateverItsHitsFind) {
    // The blocker comes over the growing face: its hits still find the same surface, but
    // the shadow tests that light it now meet the blocker.
    RenderAllExact({Growing(2.5), Growing(3.5), Growing(4.5, 2, 2.0)});
}

}  // namespace
}  // namespace povrayfc
