// Surface hits run again: a sample whose only rays that meet a change are rays whose hit
// POV-Ray, asked again in the new frame, finds with the same surface, bit for bit, is kept.
//
// Why. A surface that changes shape in its own plane (a mesh vertex sliding along its
// triangle's plane, a box turning about its face's normal, a box growing along its face)
// ends the same camera rays at the same points with the same normal and colour, but it
// changed, so every ray that ended on it, or passed its hull, was traced again: its whole
// face, where only its edge changes.
//
// Why it is exact. A sample's trace is a sequence of computations each taking what the ones
// before it gave (shadow_replay.h). A ray's search for its nearest surface takes the ray
// (origin, direction, flags, maximum depth) and gives a hit; what the trace then does with
// the hit reads the hit's depth and point, the surface's normal there (raw, and as each
// texture layer's normal pattern bends it), its uv coordinates, each layer's pigment colour
// and finish, the object's flags and interior, and the ray. The patch layer describes all of
// that in one 64-bit signature (fc-scene/surface_hits.h), computed by the same code when the
// hit is recorded and when it is run again. When every segment of the sample but such hits
// is clean, every input of each hit's search is what it was; POV-Ray's own search, run again
// on it in the new frame, gives what the new frame's trace would give, and when its
// signature is the one recorded, everything after the hit is what it was, by induction the
// whole trace, and so the colour. A hit whose surface the signature cannot describe (layered
// texture maps, light groups, a ray inside an object, and so on) is not kept.
//
// Unlike a shadow test, a kept hit's segment is exactly the new frame's: the same ray to the
// same depth. Only the unit it names changes (the hit object's unit has a new id when it
// changed, unit_ids.h), and the replay gives it: the segment is rewritten in place, and the
// sample is as good as traced.
//
// Which hits are kept: a sample traced again because a change reached it keeps its first
// kMaxSurfaceHits hits (the change that reached it may well reach it again next frame); a
// sample traced where nothing was recorded keeps none, so the first frame pays nothing.
#ifndef POVRAYFC_SURFACE_REPLAY_H
#define POVRAYFC_SURFACE_REPLAY_H

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

namespace povrayfc {

// One ray's search for its nearest surface, with everything it took and a signature of what
// it found. Plain data, filled by the patch layer through RecordSurfaceHit (ray_recording.h).
struct SurfaceHit {
    std::uint16_t rayFlags = 0;  // POV-Ray's flags of the ray (the patch layer numbers them)
    double origin[3] = {0, 0, 0};
    double direction[3] = {0, 0, 0};
    double maxDepth = 0;         // the depth the search was limited to (0: none)
    std::uint64_t signature = 0; // what it found (fc-scene/surface_hits.h)
    std::uint32_t segment = 0;   // which of the sample's segments it is
};

// The search again, in the frame being rendered: implemented by the patch layer with
// POV-Ray's own search. Writes the signature of what it found and the parser's unit index of
// the object hit (kUnitNothing when none); false when it cannot be run or described.
class SurfaceReplayer {
  public:
    virtual ~SurfaceReplayer() = default;
    virtual bool Replay(const SurfaceHit &hit, std::uint64_t &signature, std::uint32_t &unitIndex) = 0;
};

// A sample keeps at most this many (the first it traced): the camera ray and one more.
constexpr std::size_t kMaxSurfaceHits = 2;

// Packed after the sample's shadow tests: count (1 byte), then per hit ray flags (2),
// origin, direction and maximum depth (7 doubles), signature (8) and segment (4).
constexpr std::size_t kSurfaceHitBytes = 2 + 7 * 8 + 8 + 4;

void PackSurfaceHits(const std::vector<SurfaceHit> &hits, std::vector<std::uint8_t> &packed);
std::size_t SurfaceHitsBytes(const std::uint8_t *bytes);
// Reads them back into `hits` (room for kMaxSurfaceHits); returns how many there are.
std::size_t UnpackSurfaceHits(const std::uint8_t *bytes, SurfaceHit *hits);

// A signature's running hash, FNV-1a over 64-bit words: each value (8 bytes at most, as its
// bits) is one word, xored in and multiplied by an odd prime, both one-to-one, so a change
// of any one value changes the hash. The patch layer feeds it every value a hit's shading
// reads.
class SignatureHash {
  public:
    template <class T>
    void Add(const T &value) {
        static_assert(sizeof(T) <= 8, "one value at a time");
        std::uint64_t word = 0;
        std::memcpy(&word, &value, sizeof value);
        value_ = (value_ ^ word) * 0x100000001b3ull;
    }
    std::uint64_t Value() const { return value_; }

  private:
    std::uint64_t value_ = 0xcbf29ce484222325ull;
};

}  // namespace povrayfc

#endif
