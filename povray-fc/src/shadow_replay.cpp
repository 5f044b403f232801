// Shadow tests kept with a sample and run again (shadow_replay.h).
#include "povrayfc/shadow_replay.h"

#include <cstring>

#include "byte_io.h"

namespace povrayfc {

void PackShadowTests(const std::vector<ShadowTest> &tests, std::vector<std::uint8_t> &packed) {
    const std::size_t count = tests.size() < kMaxShadowTests ? tests.size() : kMaxShadowTests;
    const std::size_t at = packed.size();
    packed.resize(at + 1 + count * kShadowTestBytes);
    std::uint8_t *out = packed.data() + at;
    *out++ = std::uint8_t(count);
    for (std::size_t i = 0; i < count; ++i) {
        const ShadowTest &t = tests[i];
        Put(out, t.light);
        Put(out, t.rayFlags);
        Put(out, t.traceLevel);
        for (double v : t.origin) Put(out, v);
        for (double v : t.direction) Put(out, v);
        Put(out, t.depth);
        for (float v : t.colourIn) Put(out, v);
        for (float v : t.colourOut) Put(out, v);
        Put(out, t.firstSegment);
        Put(out, t.segmentCount);
    }
}

std::size_t ShadowTestsBytes(const std::uint8_t *bytes) { return 1 + std::size_t(bytes[0]) * kShadowTestBytes; }

std::size_t UnpackShadowTests(const std::uint8_t *bytes, ShadowTest *tests) {
    const std::size_t count = bytes[0] < kMaxShadowTests ? bytes[0] : kMaxShadowTests;
    const std::uint8_t *in = bytes + 1;
    for (std::size_t i = 0; i < count; ++i) {
        ShadowTest &t = tests[i];
        Get(in, t.light);
        Get(in, t.rayFlags);
        Get(in, t.traceLevel);
        for (double &v : t.origin) Get(in, v);
        for (double &v : t.direction) Get(in, v);
        Get(in, t.depth);
        for (float &v : t.colourIn) Get(in, v);
        for (float &v : t.colourOut) Get(in, v);
        Get(in, t.firstSegment);
        Get(in, t.segmentCount);
    }
    return count;
}

bool ShadowTestsHold(const ShadowTest *tests, std::size_t count, ShadowReplayer *replayer, bool cachesMatter,
                     ShadowRun *runs) {
    if (!replayer) return false;
    for (std::size_t i = 0; i < count; ++i) {
        float colour[3];
        runs[i] = ShadowRun();
        if (!replayer->Replay(tests[i], colour, runs[i])) return false;
        // Where a filtering object may be cached, the next test would try it first.
        if (cachesMatter && runs[i].cached) return false;
        // The same bits: -0 is not +0 to what follows (a sign may reach a division).
        if (std::memcmp(colour, tests[i].colourOut, sizeof colour) != 0) return false;
    }
    return true;
}

}  // namespace povrayfc
