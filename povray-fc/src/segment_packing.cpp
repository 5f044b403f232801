// Segment packing: writing a sample's segments compactly and reading them back.
#include "povrayfc/segment_packing.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "povrayfc/sample_store.h"

namespace povrayfc {

namespace {

using namespace packing;

// The derived fields. The packer and the unpacker both call these (never inlined, so
// that both run the very same instructions: no contraction into fused multiply-adds in
// one caller and not the other), so the value the packer checks is the value read back.

// The end of segment `s`: origin + length * direction. The float products are exact in
// double; the sum rounds once to double, once to float.
__attribute__((noinline)) void EndOf(const Segment &s, float out[3]) {
    for (int c = 0; c < 3; ++c) out[c] = float(double(s.origin[c]) + double(s.length) * double(s.direction[c]));
}

// The unit vector from `origin` towards `apex`, and the distance; false when they coincide.
__attribute__((noinline)) bool TowardApex(const float origin[3], const double apex[3], float direction[3],
                                          double &distance) {
    const double v[3] = {apex[0] - double(origin[0]), apex[1] - double(origin[1]), apex[2] - double(origin[2])};
    const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (!(n > 0.0) || !std::isfinite(n)) return false;
    for (int c = 0; c < 3; ++c) direction[c] = float(v[c] / n);
    distance = n;
    return true;
}

// The length, in units of `direction`, from `origin` to `apex`, rounded up to a float.
__attribute__((noinline)) float LengthToApex(const float origin[3], const float direction[3], const double apex[3]) {
    const double v[3] = {apex[0] - double(origin[0]), apex[1] - double(origin[1]), apex[2] - double(origin[2])};
    const double d[3] = {double(direction[0]), double(direction[1]), double(direction[2])};
    const double length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) / std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    float f = float(length);
    if (double(f) < length) f = std::nextafter(f, std::numeric_limits<float>::infinity());
    return f;
}

// Octahedral coordinates of a unit vector, each as a signed 24-bit integer.
constexpr double kOctScale = double((1 << 23) - 1);

void OctEncode(const double d[3], std::int32_t q[2]) {
    const double l1 = std::fabs(d[0]) + std::fabs(d[1]) + std::fabs(d[2]);
    double u = d[0] / l1, v = d[1] / l1;
    if (d[2] < 0.0) {
        const double fu = (1.0 - std::fabs(v)) * (u >= 0.0 ? 1.0 : -1.0);
        const double fv = (1.0 - std::fabs(u)) * (v >= 0.0 ? 1.0 : -1.0);
        u = fu;
        v = fv;
    }
    q[0] = std::int32_t(std::lround(std::clamp(u, -1.0, 1.0) * kOctScale));
    q[1] = std::int32_t(std::lround(std::clamp(v, -1.0, 1.0) * kOctScale));
}

__attribute__((noinline)) void OctDecode(const std::int32_t q[2], float out[3]) {
    const double u = double(q[0]) / kOctScale, v = double(q[1]) / kOctScale;
    double d[3] = {u, v, 1.0 - std::fabs(u) - std::fabs(v)};
    if (d[2] < 0.0) {
        d[0] = (1.0 - std::fabs(v)) * (u >= 0.0 ? 1.0 : -1.0);
        d[1] = (1.0 - std::fabs(u)) * (v >= 0.0 ? 1.0 : -1.0);
    }
    const double n = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (int c = 0; c < 3; ++c) out[c] = float(d[c] / n);
}

double MaxAbs(const double v[3]) { return std::max(std::fabs(v[0]), std::max(std::fabs(v[1]), std::fabs(v[2]))); }

// Whether the float vector `f` is within kPackTolerance of `v` (relative to v's largest
// component). NaN is never within.
bool Within(const float f[3], const double v[3]) {
    const double tolerance = kPackTolerance * MaxAbs(v);
    for (int c = 0; c < 3; ++c)
        if (!(std::fabs(double(f[c]) - v[c]) <= tolerance)) return false;
    return true;
}

bool IsApex(const FanApexes &apexes, std::uint8_t fan, bool origin) {
    return fan < apexes.count && apexes.isOrigin[fan] == origin;
}

void Put(std::vector<std::uint8_t> &out, const void *p, std::size_t n) {
    const auto *b = static_cast<const std::uint8_t *>(p);
    out.insert(out.end(), b, b + n);
}

void PutInt24(std::vector<std::uint8_t> &out, std::int32_t v) {
    const std::uint32_t u = std::uint32_t(v);
    out.push_back(std::uint8_t(u));
    out.push_back(std::uint8_t(u >> 8));
    out.push_back(std::uint8_t(u >> 16));
}

std::int32_t GetInt24(const std::uint8_t *p) {
    std::uint32_t u = std::uint32_t(p[0]) | (std::uint32_t(p[1]) << 8) | (std::uint32_t(p[2]) << 16);
    if (u & 0x800000u) u |= 0xff000000u;  // sign-extend
    return std::int32_t(u);
}

std::size_t UnitBytes(std::uint8_t flags) {
    switch (flags & kUnitMask) {
        case kUnitShort: return 2;
        case kUnitLong: return 4;
        default: return 0;
    }
}

// Bytes after the header (fan and flags) up to the unit field.
std::size_t BodyBytes(std::uint8_t flags) {
    std::size_t n = 0;
    const std::uint8_t origin = flags & kOriginMask;
    if (origin == kOriginSameAs || origin == kOriginEndOf) n += 1;
    if (origin == kOriginExplicit) n += 12;
    const std::uint8_t direction = flags & kDirectionMask;
    if (direction == kDirectionExplicit) n += 12;
    if (direction == kDirectionOctahedral) n += 6;
    if (!(flags & kLengthToApex)) n += 4;
    return n;
}

std::uint32_t ReadUnit(const std::uint8_t *field, std::uint8_t flags) {
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
        default: {
            double distance;
            if (!IsApex(apexes, fan, false) || !TowardApex(s.origin, apexes.point[fan], s.direction, distance))
                return nullptr;
        }
    }
    if (flags & kLengthToApex) {
        if (!IsApex(apexes, fan, false)) return nullptr;
        s.length = LengthToApex(s.origin, s.direction, apexes.point[fan]);
    } else {
        std::memcpy(&s.length, p, 4);
        p += 4;
    }
    s.unit = ReadUnit(p, flags);
    p += UnitBytes(flags);
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
    bool derived = false;
    if (IsApex(apexes, fan, true)) {
        for (int c = 0; c < 3; ++c) packed.origin[c] = float(apexes.point[fan][c]);
        if (Within(packed.origin, origin)) {
            flags |= kOriginApex;
            derived = true;
        }
    }
    const std::size_t farthest = std::min(count, kMaxReference);
    for (std::size_t back = 1; !derived && back <= farthest; ++back) {
        const Segment &from = earlier[count - back];
        if (Within(from.origin, origin)) {
            std::copy(from.origin, from.origin + 3, packed.origin);
            flags |= kOriginSameAs;
        } else if (std::isfinite(from.length)) {
            EndOf(from, packed.origin);
            if (!Within(packed.origin, origin)) continue;
            flags |= kOriginEndOf;
        } else {
            continue;
        }
        reference = std::uint8_t(back - 1);
        derived = true;
    }
    if (!derived) std::copy(plain.origin, plain.origin + 3, packed.origin);

    // The direction: a shadow test's pieces share theirs; a light's shadow rays aim at it.
    std::int32_t oct[2] = {0, 0};
    double distance = 0.0;
    if (count > 0 && Within(earlier[count - 1].direction, direction)) {
        std::copy(earlier[count - 1].direction, earlier[count - 1].direction + 3, packed.direction);
        flags |= kDirectionSame;
    } else if (light && TowardApex(packed.origin, apexes.point[fan], packed.direction, distance) &&
               Within(packed.direction, direction)) {
        flags |= kDirectionToApex;
    } else {
        OctEncode(direction, oct);
        OctDecode(oct, packed.direction);
        if (Within(packed.direction, direction))
            flags |= kDirectionOctahedral;
        else
            std::copy(plain.direction, plain.direction + 3, packed.direction);
    }

    // The length: a shadow ray that reached its light ends there.
    packed.length = plain.length;
    if (light) {
        const float toApex = LengthToApex(packed.origin, packed.direction, apexes.point[fan]);
        // Never shorter than what was traced, and not longer than a hair more.
        if (double(toApex) >= tmax && double(toApex) <= tmax * (1.0 + 0x1p-20) + 1e-30) {
            packed.length = toApex;
            flags |= kLengthToApex;
        }
    }

    packed.unit = unit;
    if (unit != Segment::kNoUnit)
        flags |= (unit & ~Segment::kOpaqueBlocker) < 0x8000u ? kUnitShort : kUnitLong;

    out.push_back(fan);
    out.push_back(flags);
    const std::uint8_t originMode = flags & kOriginMask;
    if (originMode == kOriginSameAs || originMode == kOriginEndOf) out.push_back(reference);
    if (originMode == kOriginExplicit) Put(out, packed.origin, 12);
    if ((flags & kDirectionMask) == kDirectionExplicit) Put(out, packed.direction, 12);
    if ((flags & kDirectionMask) == kDirectionOctahedral) {
        PutInt24(out, oct[0]);
        PutInt24(out, oct[1]);
    }
    if (!(flags & kLengthToApex)) Put(out, &packed.length, 4);
    if ((flags & kUnitMask) == kUnitShort) {
        const std::uint32_t v = (unit & 0x7fffu) | ((unit & Segment::kOpaqueBlocker) ? 0x8000u : 0u);
        out.push_back(std::uint8_t(v));
        out.push_back(std::uint8_t(v >> 8));
    } else if ((flags & kUnitMask) == kUnitLong) {
        Put(out, &unit, 4);
    }
    return true;
}

bool UnpackSample(const std::uint8_t *bytes, std::uint32_t count, const FanApexes &apexes,
                  std::vector<Segment> &segments, std::vector<std::uint8_t> &fanOf,
                  std::vector<std::uint32_t> *headers) {
    const std::size_t first = segments.size();
    segments.resize(first + count);
    fanOf.resize(fanOf.size() + count);
    std::uint8_t *fans = fanOf.data() + fanOf.size() - count;
    const std::uint8_t *p = bytes;
    for (std::uint32_t i = 0; i < count; ++i) {
        if (headers) headers->push_back(std::uint32_t(p - bytes));
        p = UnpackOne(p, segments.data() + first, i, apexes, segments[first + i], fans[i]);
        if (!p) return false;
    }
    return true;
}

const std::uint8_t *NextPacked(const std::uint8_t *header, std::uint32_t &unit) {
    const std::uint8_t flags = header[1];
    const std::uint8_t *field = header + 2 + BodyBytes(flags);
    unit = ReadUnit(field, flags);
    return field + UnitBytes(flags);
}

std::size_t PackedSize(const std::uint8_t *bytes, std::uint32_t count) {
    const std::uint8_t *p = bytes;
    for (std::uint32_t i = 0; i < count; ++i) p += 2 + BodyBytes(p[1]) + UnitBytes(p[1]);
    return std::size_t(p - bytes);
}

std::uint64_t PackedUnitMask(const std::uint8_t *bytes, std::uint32_t count) {
    std::uint64_t mask = 0;
    const std::uint8_t *p = bytes;
    for (std::uint32_t i = 0; i < count; ++i) {
        std::uint32_t unit;
        p = NextPacked(p, unit);
        if (unit != Segment::kNoUnit) mask |= UnitMaskBit(unit & ~Segment::kOpaqueBlocker);
    }
    return mask;
}

bool RewritePackedUnit(std::uint8_t *header, std::uint32_t unit) {
    const std::uint8_t flags = header[1];
    std::uint8_t *field = header + 2 + BodyBytes(flags);
    switch (flags & kUnitMask) {
        case kUnitShort: {
            if ((unit & ~Segment::kOpaqueBlocker) >= 0x8000u) return false;
            const std::uint32_t v = (unit & 0x7fffu) | ((unit & Segment::kOpaqueBlocker) ? 0x8000u : 0u);
            field[0] = std::uint8_t(v);
            field[1] = std::uint8_t(v >> 8);
            return true;
        }
        case kUnitLong:
            std::memcpy(field, &unit, 4);
            return true;
        default: return false;
    }
}

}  // namespace povrayfc
