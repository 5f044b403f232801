// Shadow tests run again: a sample whose only rays that meet a change are shadow tests that
// passed something letting light through is kept when POV-Ray, asked those tests again in
// the new frame, gives the light the same colour, bit for bit.
//
// Why. A filtering object that moves or changes shape dirties every shadow test that passed
// it (it ended pieces of them, README.md "Units"), so the whole of its shadow is traced
// again though only its edge changes colour: light through a uniformly tinted surface takes
// the same tint wherever it crosses.
//
// Why it is exact. A sample's trace is a sequence of computations each of which takes what
// the ones before it gave; a shadow test takes its ray (origin, direction), the distance to
// the light, the light's colour before it, the ray's flags and the trace level, and gives
// the light's colour after it. When every segment of the sample but the pieces of such
// tests is clean, every input of each test is what it was; POV-Ray's own shadow test
// (Trace::TracePointLightShadowRay), run again on those inputs in the new frame, gives what
// the test would give there, and when that is the colour it gave before, everything after it
// is what it was, by induction the whole trace, and so the colour. The test also reads and
// writes the thread's shadow caches (the object that last shadowed fully, per light): where
// a filtering object may be cached, a test is kept only when the caches held nothing as it
// started (the sample's earlier tests, clean or run again, then leave them as empty in the
// new frame), and is run again with them empty; a run that would leave an object in them
// (it now met an opaque surface before any transparent one) does not hold. Where nothing
// lets light through, only opaque surfaces are cached, and a cached one that does not block
// leaves the test to the loop (patch 0201): what the caches hold changes no test's colour,
// so there tests that started with a cached object, and tests an opaque surface answered,
// are kept too (ray_recording.h). The patch layer keeps the other thread state a shadow test
// can read out of it: scenes with media, fog, photons, radiosity, subsurface scattering or
// isosurfaces (whose root finder keeps a cache across rays) keep no shadow tests
// (fc-scene/shadow_tests.h).
//
// The kept sample's pieces of the test stay those of the old frame: they lie on the same
// line from the same origin to the light, split where the old surfaces were, so a later
// change anywhere on the test's way still meets one of them, and a later change of the
// objects it passed still ends one of them, which runs the test again. Where every test run
// again is one piece that passed nothing then and now and ended alike (at the light, or on
// an opaque surface, renamed to the one that answers now), its pieces are the new frame's
// and the sample is not stale (block_tracer.cpp, TestsAsTraced).
#ifndef POVRAYFC_SHADOW_REPLAY_H
#define POVRAYFC_SHADOW_REPLAY_H

#include <cstddef>
#include <cstdint>
#include <vector>

namespace povrayfc {

// One shadow test that passed something that lets light through, with everything it took
// and what it gave. Plain data: filled by ShadowSegmentRecord (ray_recording.h).
struct ShadowTest {
    std::uint16_t light;       // the light's index among the scene's lights
    std::uint16_t rayFlags;    // POV-Ray's flags of the test's ray (the patch layer numbers them)
    std::uint8_t traceLevel;   // the trace level it ran at (which shadow cache it would fill)
    double origin[3];
    double direction[3];
    double depth;              // the distance to the light it started with
    float colourIn[3];         // the light's colour it started with
    float colourOut[3];        // and the colour it gave
    std::uint32_t firstSegment;  // its pieces: the sample's segments [firstSegment, + segmentCount)
    std::uint16_t segmentCount;
};

// What a test run again did besides the colour it gave.
struct ShadowRun {
    bool passed = false;  // it passed something (its loop moved its origin)
    bool cached = false;  // it left an object in the shadow caches
    // The parser's unit index of the opaque surface that answered it (kUnitNothing: none),
    // as its ShadowSegmentRecord::BlockedAt was told.
    std::uint32_t blocker = 0xffffffffu;
};

// The test again, in the frame being rendered: implemented by the patch layer with POV-Ray's
// own shadow test, its shadow caches empty. Writes the colour it gives and what else it did;
// false when it cannot be run as described.
class ShadowReplayer {
  public:
    virtual ~ShadowReplayer() = default;
    virtual bool Replay(const ShadowTest &test, float colourOut[3], ShadowRun &run) = 0;
};

// A sample keeps at most this many (the first it traced); the others' pieces are tested as
// every other segment is.
constexpr std::size_t kMaxShadowTests = 4;

// The tests a sample keeps are packed after its segments (and tied searches) in
// BlockRecord::packed: count (1 byte), then per test light (2), ray flags (2), trace level
// (1), origin, direction and depth (7 doubles), colours (6 floats), first segment (4) and
// segment count (2).
constexpr std::size_t kShadowTestBytes = 2 + 2 + 1 + 7 * 8 + 6 * 4 + 4 + 2;

void PackShadowTests(const std::vector<ShadowTest> &tests, std::vector<std::uint8_t> &packed);
std::size_t ShadowTestsBytes(const std::uint8_t *bytes);
// Reads them back into `tests` (room for kMaxShadowTests); returns how many there are.
std::size_t UnpackShadowTests(const std::uint8_t *bytes, ShadowTest *tests);

// Runs `tests` (as UnpackShadowTests gave them) again through `replayer` and says whether
// each gave the colour it gave before, bit for bit, and (when `cachesMatter`) left nothing
// in the shadow caches; it stops at the first that did not. `runs` (room for count): what
// each did.
bool ShadowTestsHold(const ShadowTest *tests, std::size_t count, ShadowReplayer *replayer, bool cachesMatter,
                     ShadowRun *runs);

}  // namespace povrayfc

#endif
