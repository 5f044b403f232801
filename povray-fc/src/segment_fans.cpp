// SegmentFans: finding a block's bundles of segments and bounding each by a cone.
#include "povrayfc/segment_fans.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace povrayfc {

namespace {


double Dot(const Vec3 &a, const Vec3 &b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
double Norm(const Vec3 &a) { return std::sqrt(Dot(a, a)); }
Vec3 Cross(const Vec3 &a, const Vec3 &b) {
    return Vec3{a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
double MaxAbs(const Vec3 &a) { return std::max(std::fabs(a.x), std::max(std::fabs(a.y), std::fabs(a.z))); }
Vec3 Origin(const Segment &s) { return Vec3{s.origin[0], s.origin[1], s.origin[2]}; }
Vec3 Direction(const Segment &s) { return Vec3{s.direction[0], s.direction[1], s.direction[2]}; }

// The directions from the apex that hold one segment (at most two), its reach and slack.
struct Sweep {
    Vec3 u[2];
    int count = 0;
    double reach = 0, slack = 0, originReach = 0;
    double arc = 0;  // angle between u[0] and u[1]
};

Sweep SweepOf(const Segment &s, const Vec3 &apex) {
    Sweep w;
    const Vec3 o = Origin(s), d = Direction(s), oa = o - apex;
    const double no = Norm(oa), scale = 1.0 + MaxAbs(apex) + no;
    const double near = 1e-9 * scale;
    w.originReach = no;
    if (no > near) w.u[w.count++] = (1.0 / no) * oa;
    if (!std::isfinite(s.length)) {
        w.u[w.count++] = (1.0 / Norm(d)) * d;
        w.reach = std::numeric_limits<double>::infinity();
        return w;
    }
    const Vec3 ea = oa + double(s.length) * d;
    const double ne = Norm(ea);
    if (ne <= 1e-6 * scale) {
        // Ends at the apex (a shadow ray that reached its light): the segment from its
        // origin to the apex, give or take where its end really is.
        w.slack = ne;
        w.reach = no;
    } else {
        w.u[w.count++] = (1.0 / ne) * ea;
        w.reach = std::max(no, ne);
    }
    if (w.count == 0) w.slack = std::max(w.slack, no);  // a point at the apex
    if (w.count == 2) w.arc = std::acos(std::clamp(Dot(w.u[0], w.u[1]), -1.0, 1.0));
    return w;
}




// Bounds the members of one fan (indices into segments) by a cone around `apex`.
SegmentFan Cone(const Segment *segments, const std::vector<std::uint32_t> &members, const Vec3 &apex) {
    SegmentFan fan;
    fan.apex = apex;
    fan.reach = -1.0;
    thread_local std::vector<Vec3> directions;
    directions.clear();
    Vec3 sum{0, 0, 0};
    double arc = 0;
    for (std::uint32_t i : members) {
        const Sweep w = SweepOf(segments[i], apex);
        for (int k = 0; k < w.count; ++k) {
            sum = sum + w.u[k];
            directions.push_back(w.u[k]);
        }
        fan.reach = std::max(fan.reach, w.reach * (1.0 + 1e-9));
        fan.slack = std::max(fan.slack, w.slack);
        fan.originReach = std::max(fan.originReach, w.originReach);
        arc = std::max(arc, w.arc);
    }
    const double n = Norm(sum);
    fan.axis = n > 0 ? (1.0 / n) * sum : Vec3{1, 0, 0};
    double c = 1.0;
    for (const Vec3 &u : directions) c = std::min(c, Dot(u, fan.axis));
    // Rounding of the unit vectors, dot products and acos: a hair wider.
    fan.halfAngle = std::min(M_PI, std::acos(std::clamp(c, -1.0, 1.0)) + 0.5 * arc + 1e-9);
    fan.slack = fan.slack * (1.0 + 1e-9) + 1e-12 * (1.0 + MaxAbs(apex));
    return fan;
}

// Widens `fan` (reach < 0: empty) to hold an unbounded loose segment: its origin within
// the slack of the apex, its direction within the half angle of the axis. An empty fan
// takes the first segment's origin as apex and direction as axis; BuildFans re-centres
// both once it has seen all the segments.
void GrowUnbounded(SegmentFan &fan, const Segment &s) {
    const Vec3 o = Origin(s), d = Direction(s);
    const Vec3 u = (1.0 / Norm(d)) * d;
    if (fan.reach < 0) {
        fan.apex = o;
        fan.axis = u;
        fan.halfAngle = 0.0;
        fan.reach = std::numeric_limits<double>::infinity();
    }
    const double spread = Norm(o - fan.apex) * (1.0 + 1e-9);
    fan.slack = std::max(fan.slack, spread + 1e-12 * (1.0 + MaxAbs(fan.apex)));
    fan.originReach = std::max(fan.originReach, spread);
    const double angle = std::acos(std::clamp(Dot(u, fan.axis), -1.0, 1.0));
    fan.halfAngle = std::min(M_PI, std::max(fan.halfAngle, angle + 1e-9));
}

// The cone around unbounded loose segments: apex at the centre of their origins, axis
// along their mean direction (narrower than growing from the first segment).
SegmentFan UnboundedCone(const Segment *segments, const std::vector<std::uint32_t> &members) {
    SegmentFan fan = BlockFans::NoSegments();
    if (members.empty()) return fan;
    Box origins;
    Vec3 sum{0, 0, 0};
    for (std::uint32_t i : members) {
        origins.Grow(Origin(segments[i]));
        const Vec3 d = Direction(segments[i]);
        sum = sum + (1.0 / Norm(d)) * d;
    }
    const double n = Norm(sum);
    fan.apex = 0.5 * (origins.lo + origins.hi);
    fan.axis = n > 0 ? (1.0 / n) * sum : Vec3{1, 0, 0};
    fan.halfAngle = 0.0;
    fan.reach = std::numeric_limits<double>::infinity();
    for (std::uint32_t i : members) GrowUnbounded(fan, segments[i]);
    return fan;
}

// A loose segment joins the loose box, or the unbounded cone.
void AddLoose(BlockFans &fans, const Segment &s) {
    if (!InLooseBox(s)) {
        GrowUnbounded(fans.unbounded, s);
        return;
    }
    fans.looseBox.Grow(Origin(s));
    fans.looseBox.Grow(Origin(s) + double(s.length) * Direction(s));
}

}  // namespace

BlockFans BuildFans(const Segment *segments, std::vector<std::uint8_t> &fanOf, const FanApexes &apexes) {
    BlockFans fans;
    const std::size_t count = fanOf.size();
    std::vector<std::vector<std::uint32_t>> members(std::size_t(apexes.count) + 1);
    for (std::size_t i = 0; i < count; ++i) {
        const std::uint8_t f = fanOf[i];
        members[f < apexes.count ? f : apexes.count].push_back(std::uint32_t(i));
    }
    for (int f = 0; f < apexes.count; ++f) {
        const std::vector<std::uint32_t> &m = members[std::size_t(f)];
        const double *p = apexes.point[f];
        // An origin fan's members all carry the same float origin: the apex is that, read
        // from a member (not rounded here: GCC 12 at -O2 drops a float round trip of two
        // of three vector components, so the rounding must come from memory).
        const Vec3 apex = (apexes.isOrigin[f] && !m.empty()) ? Origin(segments[m[0]]) : Vec3{p[0], p[1], p[2]};
        fans.fans.push_back(Cone(segments, m, apex));
    }
    // The rest (reflections, refractions: they share no point) is tested segment by
    // segment; the box around its finite segments spares even that when no change comes
    // near it.
    std::vector<std::uint32_t> unbounded;
    for (std::uint32_t i : members.back()) {
        if (InLooseBox(segments[i]))
            AddLoose(fans, segments[i]);
        else
            unbounded.push_back(i);
    }
    fans.unbounded = UnboundedCone(segments, unbounded);
    for (std::size_t i = 0; i < count; ++i) {
        if (fanOf[i] >= fans.fans.size()) fanOf[i] = BlockFans::kLoose;
        fans.looseCount += fanOf[i] == BlockFans::kLoose;
    }
    return fans;
}

BlockFans GrowFans(const BlockFans &old, const Segment *segments, std::vector<std::uint8_t> &fanOf,
                   const FanApexes &apexes, const std::vector<std::pair<std::size_t, std::size_t>> &added) {
    BlockFans fans;
    fans.fans = old.fans;
    fans.looseBox = old.looseBox;
    fans.unbounded = old.unbounded;
    fans.fans.resize(std::size_t(apexes.count));  // fans new to this block start empty
    for (std::size_t f = old.fans.size(); f < fans.fans.size(); ++f) fans.fans[f].reach = -1.0;
    std::vector<std::vector<std::uint32_t>> fresh(fans.fans.size());
    for (const auto &range : added)
        for (std::size_t i = range.first; i < range.first + range.second; ++i) {
            const std::uint8_t f = fanOf[i];
            if (f < fans.fans.size()) {
                fresh[f].push_back(std::uint32_t(i));
            } else {
                fanOf[i] = BlockFans::kLoose;
                AddLoose(fans, segments[i]);
            }
        }
    for (std::size_t f = 0; f < fans.fans.size(); ++f) {
        SegmentFan &fan = fans.fans[f];
        if (fresh[f].empty()) continue;
        if (fan.reach < 0) {
            const double *p = apexes.point[f];
            fan = Cone(segments, fresh[f], apexes.isOrigin[f] ? Origin(segments[fresh[f][0]]) : Vec3{p[0], p[1], p[2]});
            continue;
        }
        for (std::uint32_t i : fresh[f]) {
            const Sweep w = SweepOf(segments[i], fan.apex);
            for (int k = 0; k < w.count; ++k) {
                const double angle = std::acos(std::clamp(Dot(w.u[k], fan.axis), -1.0, 1.0));
                fan.halfAngle = std::min(M_PI, std::max(fan.halfAngle, angle + 0.5 * w.arc + 1e-9));
            }
            fan.reach = std::max(fan.reach, w.reach * (1.0 + 1e-9));
            fan.slack = std::max(fan.slack, w.slack * (1.0 + 1e-9) + 1e-12 * (1.0 + MaxAbs(fan.apex)));
            fan.originReach = std::max(fan.originReach, w.originReach);
        }
    }
    for (std::size_t i = 0; i < fanOf.size(); ++i) {
        if (fanOf[i] >= fans.fans.size()) fanOf[i] = BlockFans::kLoose;
        fans.looseCount += fanOf[i] == BlockFans::kLoose;
    }
    return fans;
}

namespace {

// The smallest angle between the unit vector `axis` and the directions from the apex to
// the points of the segment [a, b] (both relative to the apex, neither at it), less a
// hair for rounding. Seen from the apex the segment sweeps a great-circle arc; the
// nearest point of the arc to `axis` is either the axis projected into the arc's plane,
// when that falls inside the arc, or one of its ends.
double SmallestAngleToSegment(const Vec3 &axis, const Vec3 &a, const Vec3 &b) {
    const Vec3 ua = (1.0 / Norm(a)) * a, ub = (1.0 / Norm(b)) * b;
    double phi = std::min(std::acos(std::clamp(Dot(axis, ua), -1.0, 1.0)),
                          std::acos(std::clamp(Dot(axis, ub), -1.0, 1.0)));
    const Vec3 n = Cross(ua, ub);
    const double sn = Norm(n);
    if (sn < 1e-6) {
        // Nearly collinear with the apex: on its one side the arc is shorter than
        // asin(sn), and the ends bound it to within that; through the apex, no bound.
        return Dot(ua, ub) > 0 ? phi - std::asin(sn) - 1e-9 : 0.0;
    }
    const Vec3 un = (1.0 / sn) * n;
    const Vec3 w = axis - Dot(axis, un) * un;  // the axis in the arc's plane
    if (Dot(Cross(ua, w), un) >= 0 && Dot(Cross(w, ub), un) >= 0)
        phi = std::min(phi, std::acos(std::clamp(Norm(w), -1.0, 1.0)));
    return phi - 1e-9;
}

// The cone against a sphere (centre c, radius) or, when `segmentEnd` is given, against
// the capsule around [c, *segmentEnd]: a point within `radius` of a point P, seen from
// the apex, is at most asin(radius / |P - apex|) off the direction to P.
bool ConeMayReach(const SegmentFan &fan, const Vec3 &c, const Vec3 *segmentEnd, double radius) {
    const Vec3 v = c - fan.apex;
    double dist = Norm(v), phi;
    if (segmentEnd) {
        const Vec3 w = *segmentEnd - fan.apex, ab = w - v;
        const double len2 = Dot(ab, ab);
        const double t = len2 > 0.0 ? std::clamp(-Dot(v, ab) / len2, 0.0, 1.0) : 0.0;
        dist = Norm(v + t * ab) * (1.0 - 1e-12);  // the nearest point of the axis
        if (dist <= radius) return true;
        if (dist - radius > fan.reach) return false;
        phi = SmallestAngleToSegment(fan.axis, v, w);
    } else {
        if (dist <= radius) return true;
        if (dist - radius > fan.reach) return false;
        phi = std::acos(std::clamp(Dot(v, fan.axis) / dist, -1.0, 1.0));
    }
    const double beta = std::asin(std::min(1.0, radius / dist));
    return phi <= fan.halfAngle + beta + 1e-9;
}

}  // namespace

bool FanMayMeet(const SegmentFan &fan, const Hull &hull) {
    if (fan.reach < 0) return false;  // no segments
    const Box &b = hull.box;
    if (b.Empty()) return false;
    if (!b.IsFinite()) return true;
    const Vec3 c = 0.5 * (b.lo + b.hi), e = 0.5 * (b.hi - b.lo);
    const double h = std::max(e.x, std::max(e.y, e.z));
    // The stored segments' rounding (see SegmentMargin), bounded over the fan's origins:
    // the apex itself, or points within `reach` of it.
    const double spread = 2.0 * fan.originReach;
    const double margin = 0x1p-19 * (MaxAbs(fan.apex) + MaxAbs(fan.apex - c) + spread + h) + 1e-30;
    const double widen = fan.slack + 2.0 * margin;  // 2 > sqrt(3): max norm to length
    if (!ConeMayReach(fan, c, nullptr, Norm(e) + widen)) return false;
    // A slanted cylinder's box (a string, a rod) is far wider than the cylinder: its
    // capsule keeps the blocks that only see past it from testing every segment.
    if (!hull.hasCapsule) return true;
    return ConeMayReach(fan, hull.capsule.a, &hull.capsule.b, hull.capsule.radius + widen);
}

}  // namespace povrayfc
