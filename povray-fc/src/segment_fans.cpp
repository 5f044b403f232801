// SegmentFans: finding a block's bundles of segments and bounding each by a cone.
#include "povrayfc/segment_fans.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace povrayfc {

namespace {

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
    fan.reach = std::numeric_limits<double>::infinity();
    double c = 1.0, spread = 0.0;
    for (std::uint32_t i : members) {
        const Vec3 d = Direction(segments[i]);
        c = std::min(c, Dot((1.0 / Norm(d)) * d, fan.axis));
        spread = std::max(spread, Norm(Origin(segments[i]) - fan.apex));
    }
    // As GrowUnbounded widens, with one arc cosine for all.
    spread *= 1.0 + 1e-9;
    fan.halfAngle = std::min(M_PI, std::acos(std::clamp(c, -1.0, 1.0)) + 1e-9);
    fan.slack = spread + 1e-12 * (1.0 + MaxAbs(fan.apex));
    fan.originReach = spread;
    return fan;
}

// A loose segment joins the loose box, or the unbounded cone.
// (An opaque blocker's shadow test is never tested against a hull: block_tracer.cpp.)
void AddLoose(BlockFans &fans, const Segment &s) {
    if (!InLooseBox(s)) {
        GrowUnbounded(fans.unbounded, s);
        return;
    }
    fans.looseBox.Grow(Origin(s));
    fans.looseBox.Grow(Origin(s) + double(s.length) * Direction(s));
}

}  // namespace

namespace {

// The cones of the segments `members[f]` of each fan f, and of the loose ones in
// members[apexes.count].
BlockFans FansOfMembers(const Segment *segments, const FanApexes &apexes,
                        const std::vector<std::vector<std::uint32_t>> &members) {
    BlockFans fans;
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
    // segment; the box around its finite segments, and the cone around those to
    // infinity, spare even that when no change comes near them.
    std::vector<std::uint32_t> unbounded;
    for (std::uint32_t i : members.back()) {
        if (InLooseBox(segments[i]))
            AddLoose(fans, segments[i]);
        else
            unbounded.push_back(i);
    }
    fans.unbounded = UnboundedCone(segments, unbounded);
    return fans;
}

}  // namespace

BlockFans BuildFans(const Segment *segments, std::vector<std::uint8_t> &fanOf, const FanApexes &apexes) {
    ValidateFanNumbers(fanOf, apexes);
    std::vector<std::uint32_t> all(fanOf.size());
    for (std::size_t i = 0; i < all.size(); ++i) all[i] = std::uint32_t(i);
    return BuildFansOf(segments, fanOf.data(), apexes, all);
}

BlockFans BuildFansOf(const Segment *segments, const std::uint8_t *fanOf, const FanApexes &apexes,
                      const std::vector<std::uint32_t> &indices) {
    std::vector<std::vector<std::uint32_t>> members(std::size_t(apexes.count) + 1);
    for (std::uint32_t i : indices)
        if (segments[i].HullTested()) members[std::min<std::size_t>(fanOf[i], std::size_t(apexes.count))].push_back(i);
    return FansOfMembers(segments, apexes, members);
}

void ValidateFanNumbers(std::vector<std::uint8_t> &fanOf, const FanApexes &apexes) {
    for (std::uint8_t &f : fanOf)
        if (f >= apexes.count) f = BlockFans::kLoose;
}

namespace {

// One cone holding `parts` (reach < 0: empty): apex at the first part's, or the centre of
// theirs when they differ (the unbounded cones of groups), each part's apex offset added
// to its slack and reach; axis along the parts' mean axis, wide enough for each part's.
SegmentFan MergeCones(const std::vector<const SegmentFan *> &parts, bool centreApex) {
    SegmentFan merged = BlockFans::NoSegments();
    Box apexes;
    Vec3 sum{0, 0, 0};
    for (const SegmentFan *p : parts) {
        apexes.Grow(p->apex);
        sum = sum + p->axis;
    }
    if (parts.empty()) return merged;
    merged.apex = centreApex ? 0.5 * (apexes.lo + apexes.hi) : parts[0]->apex;
    const double n = Norm(sum);
    merged.axis = n > 1e-3 ? (1.0 / n) * sum : parts[0]->axis;
    merged.reach = 0.0;
    merged.halfAngle = 0.0;
    for (const SegmentFan *p : parts) {
        const double offset = Norm(p->apex - merged.apex) * (1.0 + 1e-9);
        const double angle = std::acos(std::clamp(Dot(p->axis, merged.axis), -1.0, 1.0));
        merged.halfAngle = std::min(M_PI, std::max(merged.halfAngle, angle + p->halfAngle + 1e-9));
        merged.reach = std::max(merged.reach, (p->reach + offset) * (1.0 + 1e-12));
        merged.slack = std::max(merged.slack, (p->slack + offset) * (1.0 + 1e-12));
        merged.originReach = std::max(merged.originReach, p->originReach + offset);
    }
    return merged;
}

}  // namespace

BlockFans MergeFans(const std::vector<BlockFans> &parts, const FanApexes &apexes) {
    BlockFans merged;
    std::vector<const SegmentFan *> cones;
    for (int f = 0; f < apexes.count; ++f) {
        cones.clear();
        for (const BlockFans &p : parts)
            if (std::size_t(f) < p.fans.size() && p.fans[std::size_t(f)].reach >= 0) cones.push_back(&p.fans[std::size_t(f)]);
        merged.fans.push_back(MergeCones(cones, false));
    }
    cones.clear();
    for (const BlockFans &p : parts) {
        merged.looseBox.Grow(p.looseBox);
        if (p.unbounded.reach >= 0) cones.push_back(&p.unbounded);
    }
    merged.unbounded = MergeCones(cones, true);
    return merged;
}

BlockFans GrowFans(const BlockFans &old, const Segment *segments, const std::uint8_t *fanOf,
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
            if (!segments[i].HullTested()) continue;
            const std::uint8_t f = fanOf[i];
            if (f < fans.fans.size())
                fresh[f].push_back(std::uint32_t(i));
            else
                AddLoose(fans, segments[i]);
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
    return fans;
}

namespace {

// The largest cosine of the angle between the unit vector `axis` and the directions from
// the apex to the points of the segment [a, b] (both relative to the apex, neither at
// it), plus a hair for rounding; above 1 when no bound holds. Seen from the apex the
// segment sweeps a great-circle arc; the nearest point of the arc to `axis` is either the
// axis projected into the arc's plane, when that falls inside the arc, or one of its ends.
double LargestCosineToSegment(const Vec3 &axis, const Vec3 &a, const Vec3 &b) {
    const Vec3 ua = (1.0 / Norm(a)) * a, ub = (1.0 / Norm(b)) * b;
    double best = std::max(Dot(axis, ua), Dot(axis, ub));
    const Vec3 n = Cross(ua, ub);
    const double sn = Norm(n);
    if (sn < 1e-6) {
        // Nearly collinear with the apex: on its one side the arc is shorter than
        // asin(sn) < 1.01 sn, and a cosine moves no more than its angle; through the
        // apex, no bound.
        return Dot(ua, ub) > 0 ? best + 1.01 * sn + 1e-12 : 2.0;
    }
    const Vec3 un = (1.0 / sn) * n;
    const Vec3 w = axis - Dot(axis, un) * un;  // the axis in the arc's plane
    if (Dot(Cross(ua, w), un) >= 0 && Dot(Cross(w, ub), un) >= 0) best = std::max(best, Norm(w));
    return best + 1e-12;
}

}  // namespace

FanTester::FanTester(const SegmentFan &fan)
    : fan_(fan), cosHalf_(std::cos(fan.halfAngle)), sinHalf_(std::sin(fan.halfAngle)) {}

// Whether a point within `radius` of a point P at distance `dist` (> radius) from the
// apex may lie in the cone, given the largest cosine `cosine` of the angle between the
// axis and the directions to the candidates P. Seen from the apex, such a point is at
// most beta = asin(radius / dist) off the direction to P, so the test is
// angle <= halfAngle + beta, done on cosines (no inverse trigonometry): cos(angle) >=
// cos(halfAngle + beta) less a hair (1e-9 in cosine is wider than 1e-9 radians).
bool FanTester::WithinAngle(double cosine, double radius, double dist) const {
    const double sinBeta = std::min(1.0, radius / dist), cosBeta = std::sqrt(1.0 - sinBeta * sinBeta);
    // halfAngle + beta >= pi: every direction (beta <= pi/2, so halfAngle >= pi/2).
    if (cosHalf_ <= 0.0 && sinBeta >= sinHalf_) return true;
    return cosine >= cosHalf_ * cosBeta - sinHalf_ * sinBeta - 1e-9;
}

bool FanTester::MayReachSphere(const Vec3 &c, double radius) const {
    const Vec3 v = c - fan_.apex;
    const double dist = Norm(v);
    if (dist <= radius) return true;
    if (dist - radius > fan_.reach) return false;
    return WithinAngle(Dot(v, fan_.axis) / dist, radius, dist);
}

bool FanTester::MayReachCapsule(const Vec3 &a, const Vec3 &b, double radius) const {
    const Vec3 v = a - fan_.apex, w = b - fan_.apex, ab = w - v;
    const double len2 = Dot(ab, ab);
    const double t = len2 > 0.0 ? std::clamp(-Dot(v, ab) / len2, 0.0, 1.0) : 0.0;
    const double dist = Norm(v + t * ab) * (1.0 - 1e-12);  // the nearest point of the axis
    if (dist <= radius) return true;
    if (dist - radius > fan_.reach) return false;
    return WithinAngle(LargestCosineToSegment(fan_.axis, v, w), radius, dist);
}

bool FanTester::MayMeet(const Hull &hull) const {
    if (fan_.reach < 0) return false;  // no segments
    const Box &b = hull.box;
    if (b.Empty()) return false;
    if (!b.IsFinite()) return true;
    const Vec3 c = 0.5 * (b.lo + b.hi), e = 0.5 * (b.hi - b.lo);
    const double h = std::max(e.x, std::max(e.y, e.z));
    // The stored segments' rounding (see SegmentMargin), bounded over the fan's origins:
    // the apex itself, or points within `reach` of it.
    const double spread = 2.0 * fan_.originReach;
    const double margin = 0x1p-19 * (MaxAbs(fan_.apex) + MaxAbs(fan_.apex - c) + spread + h) + 1e-30;
    const double widen = fan_.slack + 2.0 * margin;  // 2 > sqrt(3): max norm to length
    if (!MayReachSphere(c, Norm(e) + widen)) return false;
    // A slanted cylinder's box (a string, a rod) is far wider than the cylinder: its
    // capsule keeps the blocks that only see past it from testing every segment.
    if (!hull.hasCapsule) return true;
    return MayReachCapsule(hull.capsule.a, hull.capsule.b, hull.capsule.radius + widen);
}

bool FanMayMeet(const SegmentFan &fan, const Hull &hull) { return FanTester(fan).MayMeet(hull); }

}  // namespace povrayfc
