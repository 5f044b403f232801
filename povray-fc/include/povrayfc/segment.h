// Segment: one traced ray as a sample depends on it, stored compactly in single precision.
#ifndef POVRAYFC_SEGMENT_H
#define POVRAYFC_SEGMENT_H

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace povrayfc {

// The points origin + s * direction, s in [0, length], and the unit the ray ended on.
// Floats, not doubles: a frame keeps millions of these (32 bytes each), and every test
// against them widens the target by the rounding this costs (see SegmentMargin), so single
// precision loses no exactness, only a hair of tightness.
struct Segment {
    static constexpr std::uint32_t kNoUnit = 0xffffffffu;  // it ended on nothing (sky, light)
    // With a unit id: a shadow test that an opaque surface of the unit answered (dark,
    // whatever its colour: only the unit's shape and its staying opaque matter). Its length
    // is then the depth the test looked up to, not the blocker's (shadow_blockers.h).
    static constexpr std::uint32_t kOpaqueBlocker = 0x80000000u;

    float origin[3];
    float direction[3];
    float length;  // in units of direction; +infinity for a ray that hit nothing
    // The id (unit_ids.h) of what the ray ended on: the surface it hit, the transparent
    // object a shadow ray passed there, or the blocker of a shadow test (kOpaqueBlocker
    // added when the blocker was opaque); kNoUnit when nothing.
    std::uint32_t unit;

    std::uint32_t UnitId() const { return unit & ~kOpaqueBlocker; }
    // Whether a change's hull may alter what the ray found: not for an opaque blocker's
    // shadow test, which only what darkens it decides (shadow_blockers.h).
    bool HullTested() const { return unit == kNoUnit || !(unit & kOpaqueBlocker); }
};

// A traced length as a segment stores it: a float never shorter than `tmax` (tmax * (1 +
// 2^-22) rounds to a float above tmax: rounding to nearest moves it by at most 2^-24 of
// itself), and not below 1e-30.
inline float StoredLength(double tmax) { return tmax < 1e-30 ? 1e-30f : float(tmax * (1.0 + 0x1p-22)); }

// The segment of a traced ray, origin + t * direction for t in [0, tmax], in single
// precision. Returns false (and leaves `out` unspecified) when the ray cannot be stored
// conservatively: NaN or infinite origin or direction, a direction too small or too large
// for float, or a NaN/negative tmax. The caller must then treat the sample as depending
// on everything.
inline bool MakeSegment(const double origin[3], const double direction[3], double tmax, Segment &out) {
    // std::max, not std::fmax: fmax is a libm call here, and this runs for every ray.
    const double d0 = std::fabs(direction[0]), d1 = std::fabs(direction[1]), d2 = std::fabs(direction[2]);
    const double largest = std::max(d0, std::max(d1, d2));
    const double o = std::max(std::fabs(origin[0]), std::max(std::fabs(origin[1]), std::fabs(origin[2])));
    // NaN fails every comparison, but std::max drops a NaN in its second argument: the
    // sums carry any NaN. A direction outside float's comfortable range would break the
    // margin argument (SegmentMargin).
    const double any = origin[0] + origin[1] + origin[2] + direction[0] + direction[1] + direction[2];
    if (!(o <= 1e30 && largest <= 1e30 && largest >= 1e-20 && tmax >= 0.0 && any == any)) return false;
    // Components under 1e-30 of the largest move the ray by less than the margin over any
    // distance that matters; flushing them avoids float denormals.
    const double flush = largest * 1e-30;
    out.origin[0] = float(origin[0]);
    out.origin[1] = float(origin[1]);
    out.origin[2] = float(origin[2]);
    out.direction[0] = d0 < flush ? 0.0f : float(direction[0]);
    out.direction[1] = d1 < flush ? 0.0f : float(direction[1]);
    out.direction[2] = d2 < flush ? 0.0f : float(direction[2]);
    out.length = StoredLength(tmax);
    out.unit = Segment::kNoUnit;
    return true;
}

}  // namespace povrayfc

#endif
