// Surface hits kept with a sample and run again (surface_replay.h).
#include "povrayfc/surface_replay.h"

#include "byte_io.h"

namespace povrayfc {

void PackSurfaceHits(const std::vector<SurfaceHit> &hits, std::vector<std::uint8_t> &packed) {
    const std::size_t count = hits.size() < kMaxSurfaceHits ? hits.size() : kMaxSurfaceHits;
    const std::size_t at = packed.size();
    packed.resize(at + 1 + count * kSurfaceHitBytes);
    std::uint8_t *out = packed.data() + at;
    *out++ = std::uint8_t(count);
    for (std::size_t i = 0; i < count; ++i) {
        const SurfaceHit &h = hits[i];
        Put(out, h.rayFlags);
        for (double v : h.origin) Put(out, v);
        for (double v : h.direction) Put(out, v);
        Put(out, h.maxDepth);
        Put(out, h.signature);
        Put(out, h.segment);
    }
}

std::size_t SurfaceHitsBytes(const std::uint8_t *bytes) { return 1 + std::size_t(bytes[0]) * kSurfaceHitBytes; }

std::size_t UnpackSurfaceHits(const std::uint8_t *bytes, SurfaceHit *hits) {
    const std::size_t count = bytes[0] < kMaxSurfaceHits ? bytes[0] : kMaxSurfaceHits;
    const std::uint8_t *in = bytes + 1;
    for (std::size_t i = 0; i < count; ++i) {
        SurfaceHit &h = hits[i];
        Get(in, h.rayFlags);
        for (double &v : h.origin) Get(in, v);
        for (double &v : h.direction) Get(in, v);
        Get(in, h.maxDepth);
        Get(in, h.signature);
        Get(in, h.segment);
    }
    return count;
}

}  // namespace povrayfc
