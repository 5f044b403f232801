// SegmentFans: cones that bound a render block's stored segments, so that a block far from
// every change is found clean with a handful of tests instead of one per segment.
//
// A block's segments come in bundles: its camera rays all start at the camera, and its
// shadow rays all run towards one of a few lights. Each bundle lies inside a cone with the
// shared point as apex (the camera, or a light); a change that no cone reaches cannot meet
// any of the bundle's segments. Segments that fit no bundle (reflections, refractions)
// stay "loose": those of finite length are bounded by a box, those that hit nothing (a
// floor's reflections of the sky) by a cone from the centre of their origins, whose slack
// is the origins' spread; a change that one of these reaches tests its segments one by
// one. (A flat mirror's reflections would share the camera's mirror image, but finding
// such points cost more than it saved on Newton's cradle, where most reflections come
// from curved chrome and brass.) Which bundle a segment belongs to is known when it is
// recorded (ray_recording.h: FanApexes), so building the cones is one pass.
#ifndef POVRAYFC_SEGMENT_FANS_H
#define POVRAYFC_SEGMENT_FANS_H

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "povrayfc/geometry.h"
#include "povrayfc/hull.h"
#include "povrayfc/ray_recording.h"
#include "povrayfc/segment.h"

namespace povrayfc {

// Every segment of the fan lies within `slack` of the cone
//   { apex + s * u : |u| = 1, angle(u, axis) <= halfAngle, 0 <= s <= reach }.
// Why a cone holds a segment: seen from the apex, the directions to the points of a
// segment sweep the arc between the directions to its two ends; the angle from the axis
// along that arc exceeds the larger of its ends' by at most half the arc, so a cone that
// holds both ends, widened by half the widest member arc, holds every segment (whatever
// its width). Camera rays start at the apex and shadow rays run along a line through it,
// so their arcs are (nearly) nil. A shadow ray that reaches its light ends at the apex
// itself: it is held by the segment from its origin to the apex, plus the slack of how
// far its end misses the apex.
struct SegmentFan {
    Vec3 apex;
    Vec3 axis;                  // unit
    double halfAngle = 0.0;     // radians, up to pi
    double reach = 0.0;         // may be huge (rays that hit nothing); < 0: no segments
    double slack = 0.0;
    double originReach = 0.0;   // the farthest segment origin from the apex (bounds rounding)
};

struct BlockFans {
    static constexpr std::uint8_t kLoose = FanApexes::kLoose;  // a segment in no fan
    static constexpr std::size_t kMaxFans = FanApexes::kMax;

    std::vector<SegmentFan> fans;     // by fan number; a fan without segments has reach < 0
    Box looseBox;                     // around the loose segments of finite length
    // Around the loose segments without an end (reflections that hit nothing, bound for
    // the sky): a cone of unbounded reach from the centre of their origins, its slack
    // the origins' spread. Every point of such a ray lies within that spread of the
    // point the cone's apex reaches along the same direction; reach < 0 when none.
    SegmentFan unbounded = NoSegments();

    static SegmentFan NoSegments() {
        SegmentFan none;
        none.reach = -1.0;
        return none;
    }

    std::size_t MemoryBytes() const { return fans.capacity() * sizeof(SegmentFan); }
};

// Whether a loose segment is held by BlockFans::looseBox: rays that hit nothing end at
// POV-Ray's "infinity" (BOUND_HUGE, 2e10), and a box around them would cover everything.
inline bool InLooseBox(const Segment &s) { return s.length < 1e9f; }

// The cones around the segments of each fan, given each segment's fan (`fanOf`, from the
// recording; numbers without an apex are made kLoose) and the fans' apexes.
BlockFans BuildFans(const Segment *segments, std::vector<std::uint8_t> &fanOf, const FanApexes &apexes);

// Makes every fan number without an apex in `apexes` kLoose (BuildFans does).
void ValidateFanNumbers(std::vector<std::uint8_t> &fanOf, const FanApexes &apexes);

// The cones of some of the segments (`indices`), whose `fanOf` is valid: a group of a
// block's samples (group_fans.h).
BlockFans BuildFansOf(const Segment *segments, const std::uint8_t *fanOf, const FanApexes &apexes,
                      const std::vector<std::uint32_t> &indices);

// The fans of a replayed block (or group), cheaply: `old` were the fans of the segments it
// kept, and the segments in `added` (first index, count) were traced anew; each fan only
// widens to hold its new members. (Cones then never narrow: the caller rebuilds them from
// scratch once twice as many segments as the block holds were grown into them,
// BlockRecord::grownSegments.) `fanOf` must be valid (ValidateFanNumbers).
BlockFans GrowFans(const BlockFans &old, const Segment *segments, const std::uint8_t *fanOf,
                   const FanApexes &apexes, const std::vector<std::pair<std::size_t, std::size_t>> &added);

// Cones that hold every segment the cones of `parts` hold (for each fan, and the loose
// box and unbounded cone): a block's from its groups', without a pass over the segments.
BlockFans MergeFans(const std::vector<BlockFans> &parts, const FanApexes &apexes);

// True when a segment within `fan` may meet `hull` (conservative, including the float
// rounding of the stored segments).
bool FanMayMeet(const SegmentFan &fan, const Hull &hull);

// FanMayMeet for one fan against many hulls: the cone's cosine and sine once.
class FanTester {
  public:
    explicit FanTester(const SegmentFan &fan);
    bool MayMeet(const Hull &hull) const;

  private:
    bool MayReachSphere(const Vec3 &centre, double radius) const;
    bool MayReachCapsule(const Vec3 &a, const Vec3 &b, double radius) const;
    bool WithinAngle(double cosine, double radius, double dist) const;

    const SegmentFan &fan_;
    double cosHalf_, sinHalf_;
};

}  // namespace povrayfc

#endif
