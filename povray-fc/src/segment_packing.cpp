// Segment packing: writing a sample's segments compactly and reading them back.
#include "povrayfc/segment_packing.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace povrayfc {

namespace {

using namespace packing;

// The derived fields. The packer and the unpacker both call these, so the value the packer
// checks is the value read back: IEEE arithmetic gives the same bits wherever they are
// inlined, as long as no caller fuses a multiply and an add, which CMakeLists.txt forbids
// for this file (-ffp-contract=off).

// The end of segment `s`: origin + length * direction. The float products are exact in
// double; the sum rounds once to double, once to float.
void EndOf(const Segment &s, float out[3]) {
    for (int c = 0; c < 3; ++c) out[c] = float(double(s.origin[c]) + double(s.length) * double(s.direction[c]));
}

// The direction from `origin` towards `apex`, on the octahedron |x| + |y| + |z| = 1 (no
// square root); false when they coincide.
bool TowardApex(const float origin[3], const double apex[3], float direction[3]) {
    const double v[3] = {apex[0] - double(origin[0]), apex[1] - double(origin[1]), apex[2] - double(origin[2])};
    const double n = std::fabs(v[0]) + std::fabs(v[1]) + std::fabs(v[2]);
    if (!(n > 0.0) || !(n < std::numeric_limits<double>::infinity())) return false;
    const double inverse = 1.0 / n;
    for (int c = 0; c < 3; ++c) direction[c] = float(v[c] * inverse);
    return true;
}

// The float nearest `x`, or the one above it when that is below (nextafterf is a libm call).
float RoundedUp(double x) {
    float f = float(x);
    if (double(f) < x) {
        if (f == 0.0f) return std::numeric_limits<float>::denorm_min();
        std::uint32_t bits;
        std::memcpy(&bits, &f, 4);
        bits += f > 0.0f ? 1 : -1;  // away from zero above 0, towards it below
        std::memcpy(&f, &bits, 4);
    }
    return f;
}

// Where along the ray from `origin` along `direction` the apex lies nearest (for a ray
// aimed at it, the apex itself), in units of `direction`, rounded up to a float. No square
// root: the packer checks it against the traced length anyway.
float LengthToApex(const float origin[3], const float direction[3], const double apex[3]) {
    const double v[3] = {apex[0] - double(origin[0]), apex[1] - double(origin[1]), apex[2] - double(origin[2])};
    const double d[3] = {double(direction[0]), double(direction[1]), double(direction[2])};
    const double length = (v[0] * d[0] + v[1] * d[1] + v[2] * d[2]) / (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    return RoundedUp(length);
}

// A direction on the octahedron |x| + |y| + |z| = 1, as two signed 24-bit integers (the
// usual octahedral map, without its normalisation to the sphere: no square root to read).
// fan, flags, reference, origin, direction, length, unit
constexpr std::size_t kLongestPacked = 2 + 1 + 12 + 12 + 4 + 4;

constexpr double kOctScale = double((1 << 23) - 1);
constexpr double kOctStep = 1.0 / kOctScale;  // a multiplication, not a division, per read

// Rounds to the nearest integer (halves away from 0), inline: lrint is a libm call here.
std::int32_t Nearest(double x) { return std::int32_t(x + (x >= 0.0 ? 0.5 : -0.5)); }

void OctEncode(const double d[3], std::int32_t q[2]) {
    double u = d[0], v = d[1];
    if (d[2] < 0.0) {
        u = (1.0 - std::fabs(d[1])) * (d[0] >= 0.0 ? 1.0 : -1.0);
        v = (1.0 - std::fabs(d[0])) * (d[1] >= 0.0 ? 1.0 : -1.0);
    }
    q[0] = Nearest(std::clamp(u, -1.0, 1.0) * kOctScale);
    q[1] = Nearest(std::clamp(v, -1.0, 1.0) * kOctScale);
}

void OctDecode(const std::int32_t q[2], float out[3]) {
    const double u = double(q[0]) * kOctStep, v = double(q[1]) * kOctStep;
    const double z = 1.0 - std::fabs(u) - std::fabs(v);
    if (z < 0.0) {
        out[0] = float((1.0 - std::fabs(v)) * (u >= 0.0 ? 1.0 : -1.0));
        out[1] = float((1.0 - std::fabs(u)) * (v >= 0.0 ? 1.0 : -1.0));
    } else {
        out[0] = float(u);
        out[1] = float(v);
    }
    out[2] = float(z);
}

double MaxAbs(const double v[3]) { return std::max(std::fabs(v[0]), std::max(std::fabs(v[1]), std::fabs(v[2]))); }

// Whether the float vector `f` is within `tolerance` of `v` in every component (kPackTolerance
// of v's largest, Tolerance). NaN is never within.
double Tolerance(const double v[3]) { return kPackTolerance * MaxAbs(v); }
bool Within(const float f[3], const double v[3], double tolerance) {
    return std::fabs(double(f[0]) - v[0]) <= tolerance && std::fabs(double(f[1]) - v[1]) <= tolerance &&
           std::fabs(double(f[2]) - v[2]) <= tolerance;
}

bool IsApex(const FanApexes &apexes, std::uint8_t fan, bool origin) {
    return fan < apexes.count && apexes.isOrigin[fan] == origin;
}

// A unit id below 2^15 and the opaque-blocker bit, in 2 bytes (kUnitShort; ReadUnit).
bool FitsShort(std::uint32_t unit) { return (unit & ~Segment::kOpaqueBlocker) < 0x8000u; }
std::uint8_t *PutShortUnit(std::uint8_t *at, std::uint32_t unit) {
    const std::uint32_t v = (unit & 0x7fffu) | ((unit & Segment::kOpaqueBlocker) ? 0x8000u : 0u);
    at[0] = std::uint8_t(v);
    at[1] = std::uint8_t(v >> 8);
    return at + 2;
}

// Writes n bytes at `at` and returns the byte after them.
std::uint8_t *Put(std::uint8_t *at, const void *p, std::size_t n) {
    std::memcpy(at, p, n);
    return at + n;
}

std::uint8_t *PutInt24(std::uint8_t *at, std::int32_t v) {
    const std::uint32_t u = std::uint32_t(v);
    at[0] = std::uint8_t(u);
    at[1] = std::uint8_t(u >> 8);
    at[2] = std::uint8_t(u >> 16);
    return at + 3;
}

std::int32_t GetInt24(const std::uint8_t *p) {
    std::uint32_t u = std::uint32_t(p[0]) | (std::uint32_t(p[1]) << 8) | (std::uint32_t(p[2]) << 16);
    if (u & 0x800000u) u |= 0xff000000u;  // sign-extend
    return std::int32_t(u);
}

// Unpacks one segment at `p` (the sample's `index`-th, after `earlier`); returns the byte
// after it, or nullptr when it refers to what is not there.
const std::uint8_t *UnpackOne(const std::uint8_t *p, const Segment *earlier, std::size_t index,
                              const FanApexes &apexes, Segment &s, std::uint8_t &fan) {
    fan = p[0];
    const std::uint8_t flags = p[1];
    p += 2;
    switch (flags & kOriginMask) {
        case kOriginExplicit:
            std::memcpy(s.origin, p, 12);
            p += 12;
            break;
        case kOriginSameAs:
        case kOriginEndOf: {
            const std::size_t back = std::size_t(*p++) + 1;
            if (back > index) return nullptr;
            const Segment &from = earlier[index - back];
            if ((flags & kOriginMask) == kOriginSameAs)
                std::copy(from.origin, from.origin + 3, s.origin);
            else
                EndOf(from, s.origin);
            break;
        }
        default: {
            if (!IsApex(apexes, fan, true)) return nullptr;
            for (int c = 0; c < 3; ++c) s.origin[c] = float(apexes.point[fan][c]);
        }
    }
    switch (flags & kDirectionMask) {
        case kDirectionExplicit:
            std::memcpy(s.direction, p, 12);
            p += 12;
            break;
        case kDirectionOctahedral: {
            const std::int32_t q[2] = {GetInt24(p), GetInt24(p + 3)};
            OctDecode(q, s.direction);
            p += 6;
            break;
        }
        case kDirectionSame:
            if (index == 0) return nullptr;
            std::copy(earlier[index - 1].direction, earlier[index - 1].direction + 3, s.direction);
            break;
        default:
            if (!IsApex(apexes, fan, false) || !TowardApex(s.origin, apexes.point[fan], s.direction)) return nullptr;
    }
    if (flags & kLengthToApex) {
        if (!IsApex(apexes, fan, false)) return nullptr;
        s.length = LengthToApex(s.origin, s.direction, apexes.point[fan]);
    } else {
        std::memcpy(&s.length, p, 4);
        p += 4;
    }
    s.unit = packing::ReadUnit(p, flags);
    p += packing::UnitBytes(flags);
    if (fan >= apexes.count) fan = FanApexes::kLoose;
    return p;
}

}  // namespace

bool PackSegment(const double origin[3], const double direction[3], double tmax, std::uint32_t unit,
                 std::uint8_t fan, const Segment *earlier, std::size_t count, const FanApexes &apexes,
                 std::vector<std::uint8_t> &out, Segment &packed) {
    Segment plain;
    if (!MakeSegment(origin, direction, tmax, plain)) return false;
    std::uint8_t flags = 0;
    std::uint8_t reference = 0;
    const bool light = IsApex(apexes, fan, false);

    // The origin: the camera, or where an earlier ray of the sample started or ended.
    const double originTolerance = Tolerance(origin);
    bool derived = false;
    if (IsApex(apexes, fan, true)) {
        for (int c = 0; c < 3; ++c) packed.origin[c] = float(apexes.point[fan][c]);
        if (Within(packed.origin, origin, originTolerance)) {
            flags |= kOriginApex;
            derived = true;
        }
    }
    const std::size_t farthest = std::min(count, kMaxReference);
    for (std::size_t back = 1; !derived && back <= farthest; ++back) {
        const Segment &from = earlier[count - back];
        if (Within(from.origin, origin, originTolerance)) {
            std::copy(from.origin, from.origin + 3, packed.origin);
            flags |= kOriginSameAs;
        } else if (from.length < std::numeric_limits<float>::infinity()) {
            EndOf(from, packed.origin);
            if (!Within(packed.origin, origin, originTolerance)) continue;
            flags |= kOriginEndOf;
        } else {
            continue;
        }
        reference = std::uint8_t(back - 1);
        derived = true;
    }
    if (!derived) std::copy(plain.origin, plain.origin + 3, packed.origin);

    // The direction: a shadow test's pieces share theirs; a light's shadow rays aim at it;
    // any other takes 6 bytes on the octahedron. The traced ray is origin + t * direction,
    // t in [0, tmax]; with its direction scaled by 1/scale it is the same points for t in
    // [0, tmax * scale]. Derived directions lie on the octahedron |x| + |y| + |z| = 1
    // (scale: the traced direction's |x| + |y| + |z|); a direction written in full is not
    // scaled.
    const double l1 = std::fabs(direction[0]) + std::fabs(direction[1]) + std::fabs(direction[2]);
    const double inverse = 1.0 / l1;
    const double onOctahedron[3] = {direction[0] * inverse, direction[1] * inverse, direction[2] * inverse};
    const double directionTolerance = Tolerance(onOctahedron);
    std::int32_t oct[2] = {0, 0};
    double scale = l1;
    if (count > 0 && Within(earlier[count - 1].direction, onOctahedron, directionTolerance)) {
        std::copy(earlier[count - 1].direction, earlier[count - 1].direction + 3, packed.direction);
        flags |= kDirectionSame;
    } else if (light && TowardApex(packed.origin, apexes.point[fan], packed.direction) &&
               Within(packed.direction, onOctahedron, directionTolerance)) {
        flags |= kDirectionToApex;
    } else {
        OctEncode(onOctahedron, oct);
        OctDecode(oct, packed.direction);
        if (Within(packed.direction, onOctahedron, directionTolerance)) {
            flags |= kDirectionOctahedral;
        } else {
            std::copy(plain.direction, plain.direction + 3, packed.direction);
            scale = 1.0;
        }
    }

    // The length, in units of the stored direction, rounded up as MakeSegment does; a
    // shadow ray that reached its light ends there.
    const double span = tmax * scale;
    packed.length = StoredLength(span);
    if (light) {
        const float toApex = LengthToApex(packed.origin, packed.direction, apexes.point[fan]);
        // Never shorter than what was traced, and not longer than a hair more.
        if (double(toApex) >= span && double(toApex) <= span * (1.0 + 0x1p-20) + 1e-30) {
            packed.length = toApex;
            flags |= kLengthToApex;
        }
    }

    packed.unit = unit;
    if (unit != Segment::kNoUnit)
        flags |= FitsShort(unit) ? kUnitShort : kUnitLong;

    // Written in place past the end, then trimmed: no call to copy a dozen bytes.
    const std::size_t start = out.size();
    out.resize(start + kLongestPacked);
    std::uint8_t *at = out.data() + start;
    *at++ = fan;
    *at++ = flags;
    const std::uint8_t originMode = flags & kOriginMask;
    if (originMode == kOriginSameAs || originMode == kOriginEndOf) *at++ = reference;
    if (originMode == kOriginExplicit) at = Put(at, packed.origin, 12);
    if ((flags & kDirectionMask) == kDirectionExplicit) at = Put(at, packed.direction, 12);
    if ((flags & kDirectionMask) == kDirectionOctahedral) {
        at = PutInt24(at, oct[0]);
        at = PutInt24(at, oct[1]);
    }
    if (!(flags & kLengthToApex)) at = Put(at, &packed.length, 4);
    if ((flags & kUnitMask) == kUnitShort) {
        at = PutShortUnit(at, unit);
    } else if ((flags & kUnitMask) == kUnitLong) {
        at = Put(at, &unit, 4);
    }
    out.resize(std::size_t(at - out.data()));
    return true;
}

bool UnpackSample(const std::uint8_t *bytes, std::uint32_t count, const FanApexes &apexes, Segment *segments,
                  std::uint8_t *fanOf, std::uint32_t *headers) {
    const std::uint8_t *p = bytes;
    for (std::uint32_t i = 0; i < count; ++i) {
        if (headers) headers[i] = std::uint32_t(p - bytes);
        p = UnpackOne(p, segments, i, apexes, segments[i], fanOf[i]);
        if (!p) return false;
    }
    return true;
}

bool RewritePackedUnit(std::uint8_t *header, std::uint32_t unit) {
    const std::uint8_t flags = header[1];
    std::uint8_t *field = header + 2 + packing::BodyBytes(flags);
    switch (flags & kUnitMask) {
        case kUnitShort:
            if (!FitsShort(unit)) return false;
            PutShortUnit(field, unit);
            return true;
        case kUnitLong:
            std::memcpy(field, &unit, 4);
            return true;
        default: return false;
    }
}

}  // namespace povrayfc
