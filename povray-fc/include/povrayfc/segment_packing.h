// Segment packing: a sample's ray segments as the store keeps them, 3 to 34 bytes each
// where a Segment and its bundle number take 33.
//
// Why. A deep glass scene records about 27 segments per camera sample, and at 33 bytes
// they were nine tenths of the store. Most of a segment repeats what its sample already
// holds: a shadow ray leaves the point a ray before it hit (or the point another shadow
// ray left), towards a light the block's bundles know (FanApexes); a reflected ray leaves
// where its parent ended; a shadow test's pieces share one direction; a camera ray starts
// at the camera. The packed form says so in a flag and at most one byte instead of 12 or
// 24, and a direction it cannot derive takes 6 bytes (octahedral, 24 bits a side).
//
// Why it stays exact. A derived field is not the float nearest the traced double value, so
// the packer keeps one only when the value unpacking will give (computed by the very
// functions the unpacker calls) lies within kPackTolerance of the traced value: origin and
// direction in the max norm, relative to their largest component; and a derived length
// only when it is not shorter than the traced one. Otherwise the field is written in full
// as MakeSegment rounds it. An octahedral direction is the traced one scaled onto the
// octahedron |x| + |y| + |z| = 1 (reading it back takes no square root), and its length
// is scaled the other way: the same points, another parametrisation of the ray. SegmentMargin (hull.h) is four times what that error can move
// the ray near a target; povray-fc/README.md "Conservative in floating point".
//
// Layout of one packed segment, in this order:
//   fan (1 byte: the bundle number, FanApexes, or kLoose)
//   flags (1 byte, below)
//   reference (1 byte, origin modes kOriginSameAs and kOriginEndOf: how many segments
//              back, 0 = the one just before)
//   origin (12 bytes, 3 floats, kOriginExplicit)
//   direction (12 bytes, 3 floats, kDirectionExplicit; 6 bytes, kDirectionOctahedral)
//   length (4 bytes, a float, unless kLengthToApex)
//   unit (2 bytes, kUnitShort; 4 bytes, kUnitLong; nothing, kUnitNone)
// A sample's segments are packed one after the other; a reference never leaves the sample,
// so each sample unpacks on its own.
#ifndef POVRAYFC_SEGMENT_PACKING_H
#define POVRAYFC_SEGMENT_PACKING_H

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "povrayfc/fan_apexes.h"
#include "povrayfc/segment.h"

namespace povrayfc {

// How far a derived origin or direction may lie from the traced one, relative to its
// largest component (a float's own rounding is 2^-24).
constexpr double kPackTolerance = 0x1p-21;

namespace packing {
enum : std::uint8_t {
    kOriginExplicit = 0,
    kOriginSameAs = 1,   // the origin of an earlier segment of the sample
    kOriginEndOf = 2,    // the end of an earlier segment (origin + length * direction)
    kOriginApex = 3,     // the apex of its fan, an origin fan (the camera)
    kOriginMask = 3,

    kDirectionExplicit = 0 << 2,
    kDirectionOctahedral = 1 << 2,  // on the octahedron |x|+|y|+|z| = 1, 24 bits a side
    kDirectionSame = 2 << 2,        // the previous segment's
    kDirectionToApex = 3 << 2,      // from its origin towards its fan's apex (a light), unit
    kDirectionMask = 3 << 2,

    kLengthToApex = 1 << 4,  // from its origin to its fan's apex, rounded up

    kUnitNone = 0 << 5,
    kUnitShort = 1 << 5,  // 15 bits of id and the opaque-blocker bit
    kUnitLong = 2 << 5,
    kUnitMask = 3 << 5,
};
// How far back an origin may refer.
constexpr std::size_t kMaxReference = 64;

// The bytes of a packed segment with these flags after its fan and flags, up to its unit;
// and its unit's. Inline: walking a sample's units runs for every sample of a block whose
// units changed.
constexpr std::size_t BodyBytes(std::uint8_t flags) {
    const std::uint8_t origin = flags & kOriginMask, direction = flags & kDirectionMask;
    return (origin == kOriginSameAs || origin == kOriginEndOf ? 1 : origin == kOriginExplicit ? 12 : 0) +
           (direction == kDirectionExplicit ? 12 : direction == kDirectionOctahedral ? 6 : 0) +
           ((flags & kLengthToApex) ? 0 : 4);
}
constexpr std::size_t UnitBytes(std::uint8_t flags) {
    return (flags & kUnitMask) == kUnitShort ? 2 : (flags & kUnitMask) == kUnitLong ? 4 : 0;
}
inline std::uint32_t ReadUnit(const std::uint8_t *field, std::uint8_t flags) {
    switch (flags & kUnitMask) {
        case kUnitShort: {
            const std::uint32_t v = std::uint32_t(field[0]) | (std::uint32_t(field[1]) << 8);
            return (v & 0x7fffu) | ((v & 0x8000u) ? Segment::kOpaqueBlocker : 0u);
        }
        case kUnitLong: {
            std::uint32_t v;
            std::memcpy(&v, field, 4);
            return v;
        }
        default: return Segment::kNoUnit;
    }
}
}  // namespace packing

// Packs the ray origin + t * direction, t in [0, tmax], that ended on `unit` (a
// Segment::unit value) in bundle `fan` of `apexes`, after the sample's `count` segments
// before it (`earlier`, as unpacked), onto the end of `out`; `packed` is set to what
// unpacking will give. Returns false, appending nothing, when the ray cannot be stored
// conservatively (MakeSegment).
bool PackSegment(const double origin[3], const double direction[3], double tmax, std::uint32_t unit,
                 std::uint8_t fan, const Segment *earlier, std::size_t count, const FanApexes &apexes,
                 std::vector<std::uint8_t> &out, Segment &packed);

// Segments written in full: fan, flags, origin, direction and length as MakeSegment gave
// them, and the unit when there is one (34 bytes, 30 when it ended on nothing). A third of
// PackSegment's instructions, for three times the bytes: the store takes this form while
// memory is plentiful (SampleStore::PackTightly); both forms unpack alike and may share a
// record. The recorder makes the Segments as rays are traced and writes a sample's in one
// go when it ends, so a segment costs no growth of `out` of its own.
constexpr std::size_t FullBytes(std::uint32_t unit) { return unit == Segment::kNoUnit ? 30 : 34; }
inline void AppendInFull(const Segment *segments, const std::uint8_t *fans, std::size_t count,
                         std::vector<std::uint8_t> &out) {
    std::size_t bytes = 0;
    for (std::size_t i = 0; i < count; ++i) bytes += FullBytes(segments[i].unit);
    const std::size_t start = out.size();
    out.resize(start + bytes);
    std::uint8_t *at = out.data() + start;
    static_assert(offsetof(Segment, direction) == offsetof(Segment, origin) + 12 &&
                      offsetof(Segment, length) == offsetof(Segment, origin) + 24,
                  "origin, direction and length are written as one run of 28 bytes");
    for (std::size_t i = 0; i < count; ++i) {
        const Segment &s = segments[i];
        const bool unit = s.unit != Segment::kNoUnit;
        at[0] = fans[i];
        at[1] = unit ? packing::kUnitLong : packing::kUnitNone;
        std::memcpy(at + 2, s.origin, 28);
        if (unit) std::memcpy(at + 30, &s.unit, 4);
        at += unit ? 34 : 30;
    }
}

// Unpacks a sample's `count` segments packed at `bytes` into `segments` and their fans
// into `fanOf` (a fan number without an apex in `apexes` becomes kLoose), and into
// `headers`, when given, each one's offset from `bytes`: room the caller holds for
// `count` of each (UnpackScratch), so that nothing grows or is zeroed per sample (the
// test of a block's samples unpacks millions a frame). Returns false when the bytes refer
// to what is not there (an apex `apexes` lacks): the sample must then count as dirty.
bool UnpackSample(const std::uint8_t *bytes, std::uint32_t count, const FanApexes &apexes, Segment *segments,
                  std::uint8_t *fanOf, std::uint32_t *headers = nullptr);

// Scratch for unpacking samples that only grows: sized once for the largest sample (or
// block) seen, then reused as it is.
struct UnpackScratch {
    std::vector<Segment> segments;
    std::vector<std::uint8_t> fans;
    std::vector<std::uint32_t> headers;
    void Fit(std::size_t count) {
        if (segments.size() >= count) return;
        segments.resize(count);
        fans.resize(count);
        headers.resize(count);
    }
};

// Reads the unit of the packed segment whose header is at `header` (Segment::kNoUnit when
// none) and returns where the next one begins: walking a sample's units without unpacking.
inline const std::uint8_t *NextPacked(const std::uint8_t *header, std::uint32_t &unit) {
    const std::uint8_t flags = header[1];
    const std::uint8_t *field = header + 2 + packing::BodyBytes(flags);
    unit = packing::ReadUnit(field, flags);
    return field + packing::UnitBytes(flags);
}

// The bytes a sample's `count` packed segments take.
inline std::size_t PackedSize(const std::uint8_t *bytes, std::uint32_t count) {
    const std::uint8_t *p = bytes;
    for (std::uint32_t i = 0; i < count; ++i) p += 2 + packing::BodyBytes(p[1]) + packing::UnitBytes(p[1]);
    return std::size_t(p - bytes);
}

// Replaces the unit of the packed segment whose header is at `header` by `unit` (a
// Segment::unit value, not kNoUnit). False, changing nothing, when it does not fit the
// width the segment was packed with.
bool RewritePackedUnit(std::uint8_t *header, std::uint32_t unit);

}  // namespace povrayfc

#endif
