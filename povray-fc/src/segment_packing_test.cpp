// Tests for segment packing: what is read back is what the packer promised, within the
// tolerance of the traced rays, and packed small.
#include <cmath>
#include <cstring>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "povrayfc/fan_apexes.h"
#include "povrayfc/sample_store.h"
#include "povrayfc/segment_packing.h"

using namespace povrayfc;

namespace {

struct Ray {
    double origin[3], direction[3], tmax;
    std::uint32_t unit;
    std::uint8_t fan;
};

double MaxAbs(const double v[3]) { return std::max(std::fabs(v[0]), std::max(std::fabs(v[1]), std::fabs(v[2]))); }

void Normalise(double v[3]) {
    const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int c = 0; c < 3; ++c) v[c] /= n;
}

// A sample's rays as POV-Ray traces them: a camera ray, shadow tests towards two lights
// from its hit (one in pieces through a transparent object), a reflection from the hit
// and a shadow test from where that lands; `scale` moves the whole scene far from 0.
std::vector<Ray> SampleRays(std::mt19937_64 &rng, FanApexes &apexes, double scale) {
    std::uniform_real_distribution<double> u(-1, 1), len(2, 30);
    const double eye[3] = {scale + 1, scale - 2, scale - 20};
    const double lights[2][3] = {{scale + 30, scale + 40, scale - 10}, {scale - 25, scale + 35, scale + 5}};
    std::vector<Ray> rays;
    Ray camera{{eye[0], eye[1], eye[2]}, {0.3 * u(rng), 0.3 * u(rng), 1}, len(rng), 7, 0};
    Normalise(camera.direction);
    camera.fan = apexes.OriginFan(camera.origin);
    rays.push_back(camera);
    double hit[3];
    for (int c = 0; c < 3; ++c) hit[c] = camera.origin[c] + camera.tmax * camera.direction[c];
    auto shadow = [&](const double from[3], int light, bool deep, bool pieces) {
        double d[3] = {lights[light][0] - from[0], lights[light][1] - from[1], lights[light][2] - from[2]};
        double depth = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        Normalise(d);
        const std::uint8_t fan = apexes.AimFan(lights[light], deep);
        double o[3] = {from[0], from[1], from[2]};
        if (pieces) {  // through a transparent object: the loop moves its origin on
            const double passed = depth * 0.3;
            rays.push_back(Ray{{o[0], o[1], o[2]}, {d[0], d[1], d[2]}, passed, 12, fan});
            for (int c = 0; c < 3; ++c) o[c] += passed * d[c];
            depth -= passed;
        }
        rays.push_back(Ray{{o[0], o[1], o[2]}, {d[0], d[1], d[2]}, depth, Segment::kNoUnit, fan});
    };
    shadow(hit, 0, false, false);
    shadow(hit, 1, false, true);
    Ray reflected{{hit[0], hit[1], hit[2]}, {u(rng), u(rng), u(rng)}, len(rng), 40000, 0};
    Normalise(reflected.direction);
    reflected.fan = apexes.OriginFan(reflected.origin);
    rays.push_back(reflected);
    double far[3];
    for (int c = 0; c < 3; ++c) far[c] = reflected.origin[c] + reflected.tmax * reflected.direction[c];
    shadow(far, 0, true, false);
    // A ray into the sky, and one with a direction nobody normalised.
    Ray sky{{far[0], far[1], far[2]}, {u(rng), 1, u(rng)}, 2e10, Segment::kNoUnit, 0};
    Normalise(sky.direction);
    sky.fan = apexes.OriginFan(sky.origin);
    rays.push_back(sky);
    Ray odd{{hit[0], hit[1], hit[2]}, {3 * u(rng), 2, u(rng)}, len(rng), 3 | Segment::kOpaqueBlocker, 0};
    odd.fan = apexes.OriginFan(odd.origin);
    rays.push_back(odd);
    return rays;
}

// Invariant (the margin argument rests on it): an unpacked segment is the traced ray
// origin + t * direction, t in [0, tmax], in some parametrisation: its direction scaled by
// 1/k (k = 1, or onto the octahedron: k = |x| + |y| + |z|) within kPackTolerance, its
// origin within kPackTolerance, its length never shorter than tmax * k; with its unit.
bool HoldsWithScale(const Segment &s, const Ray &r, double k) {
    const double d[3] = {r.direction[0] / k, r.direction[1] / k, r.direction[2] / k};
    const double to = kPackTolerance * MaxAbs(r.origin), td = kPackTolerance * MaxAbs(d);
    for (int c = 0; c < 3; ++c)
        if (!(std::fabs(double(s.origin[c]) - r.origin[c]) <= to) || !(std::fabs(double(s.direction[c]) - d[c]) <= td))
            return false;
    return double(s.length) >= r.tmax * k;
}

void ExpectHolds(const Segment &s, const Ray &r) {
    const double l1 = std::fabs(r.direction[0]) + std::fabs(r.direction[1]) + std::fabs(r.direction[2]);
    EXPECT_TRUE(HoldsWithScale(s, r, 1.0) || HoldsWithScale(s, r, l1))
        << "origin " << s.origin[0] << " " << s.origin[1] << " " << s.origin[2] << " direction " << s.direction[0]
        << " " << s.direction[1] << " " << s.direction[2] << " length " << s.length << " tmax " << r.tmax;
    EXPECT_EQ(s.unit, r.unit);
}

// Samples packed one after the other into one record, with what the packer promised.
struct PackedSamples {
    FanApexes apexes;
    std::vector<std::uint8_t> bytes;
    std::vector<Segment> promised;
    std::vector<std::uint32_t> firsts;
    std::vector<std::vector<Ray>> samples;

    // Packs a sample's rays one by one (PackSegment), or writes them in full as MakeSegment
    // gives them, all at once (AppendInFull).
    void Add(const std::vector<Ray> &rays, bool full) {
        firsts.push_back(std::uint32_t(bytes.size()));
        std::vector<Segment> sample;
        std::vector<std::uint8_t> fans;
        std::size_t fullBytes = 0;
        for (const Ray &r : rays) {
            Segment s;
            if (full) {
                ASSERT_TRUE(MakeSegment(r.origin, r.direction, r.tmax, s));
                s.unit = r.unit;
                fullBytes += r.unit == Segment::kNoUnit ? 30u : 34u;
            } else {
                ASSERT_TRUE(PackSegment(r.origin, r.direction, r.tmax, r.unit, r.fan, sample.data(), sample.size(),
                                        apexes, bytes, s));
            }
            sample.push_back(s);
            fans.push_back(r.fan);
        }
        if (full) {
            const std::size_t before = bytes.size();
            AppendInFull(sample.data(), fans.data(), sample.size(), bytes);
            EXPECT_EQ(bytes.size() - before, fullBytes);
        }
        promised.insert(promised.end(), sample.begin(), sample.end());
        samples.push_back(rays);
    }

    // Every sample unpacks on its own to what was promised, holds its traced rays, spans
    // the bytes up to the next, and its units read without unpacking.
    void ExpectReadBack(const std::string &what) const {
        std::size_t k = 0;
        for (std::size_t i = 0; i < samples.size(); ++i) {
            const std::uint32_t count = std::uint32_t(samples[i].size());
            std::vector<Segment> segments(count);
            std::vector<std::uint8_t> fanOf(count);
            ASSERT_TRUE(UnpackSample(bytes.data() + firsts[i], count, apexes, segments.data(), fanOf.data()));
            EXPECT_EQ(PackedSize(bytes.data() + firsts[i], count),
                      (i + 1 < firsts.size() ? firsts[i + 1] : bytes.size()) - firsts[i]);
            std::uint32_t unit;
            const std::uint8_t *header = bytes.data() + firsts[i];
            for (std::size_t j = 0; j < count; ++j, ++k) {
                EXPECT_EQ(std::memcmp(&segments[j], &promised[k], sizeof(Segment)), 0) << what << ", sample " << i;
                EXPECT_EQ(fanOf[j], samples[i][j].fan);
                ExpectHolds(segments[j], samples[i][j]);
                header = NextPacked(header, unit);
                EXPECT_EQ(unit, samples[i][j].unit);
            }
        }
    }
};

TEST(SegmentPacking, WhatIsReadBackIsWhatThePackerPromisedAndHoldsTheTracedRay) {
    std::mt19937_64 rng(3);
    for (double scale : {0.0, 1.0, 1000.0, 1e6}) {
        PackedSamples record;
        for (int i = 0; i < 300; ++i) record.Add(SampleRays(rng, record.apexes, scale), false);
        record.ExpectReadBack("scale " + std::to_string(scale));
        // The point: a sample's rays mostly repeat one another (33 bytes each unpacked).
        EXPECT_LT(double(record.bytes.size()) / double(record.promised.size()), 17.0) << "scale " << scale;
    }
}

TEST(SegmentPacking, AnOriginOffByMoreThanTheToleranceIsWrittenInFull) {
    FanApexes apexes;
    std::vector<std::uint8_t> bytes;
    const double o[3] = {10, 20, 30}, d[3] = {0, 0, 1};
    Segment first;
    ASSERT_TRUE(PackSegment(o, d, 5.0, Segment::kNoUnit, FanApexes::kLoose, nullptr, 0, apexes, bytes, first));
    // Leaves (nearly) where the first ended: 35 by the floats, 4 tolerances off.
    const double near[3] = {10, 20, 35.0 + 4 * kPackTolerance * 35.0}, up[3] = {0, 1, 0};
    Segment second;
    const std::size_t before = bytes.size();
    ASSERT_TRUE(PackSegment(near, up, 1.0, Segment::kNoUnit, FanApexes::kLoose, &first, 1, apexes, bytes, second));
    EXPECT_EQ(bytes[before + 1] & packing::kOriginMask, packing::kOriginExplicit);
    EXPECT_EQ(second.origin[2], float(near[2]));
    // Within the tolerance, it refers to the first.
    const double close[3] = {10, 20, 35.0 + 0.25 * kPackTolerance * 35.0};
    const std::size_t again = bytes.size();
    ASSERT_TRUE(PackSegment(close, up, 1.0, Segment::kNoUnit, FanApexes::kLoose, &first, 1, apexes, bytes, second));
    EXPECT_EQ(bytes[again + 1] & packing::kOriginMask, packing::kOriginEndOf);
}

TEST(SegmentPacking, ALengthToTheLightIsNeverShorterThanTraced) {
    FanApexes apexes;
    const double light[3] = {0, 100, 0};
    const std::uint8_t fan = apexes.AimFan(light);
    std::mt19937_64 rng(8);
    std::uniform_real_distribution<double> u(-50, 50);
    for (int i = 0; i < 2000; ++i) {
        double o[3] = {u(rng), u(rng) / 10, u(rng)}, d[3] = {light[0] - o[0], light[1] - o[1], light[2] - o[2]};
        const double depth = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        Normalise(d);
        std::vector<std::uint8_t> bytes;
        Segment s;
        // Sometimes the test stops a hair short of the light, sometimes a hair beyond.
        const double tmax = depth * (1.0 + ((i % 3) - 1) * 1e-9);
        ASSERT_TRUE(PackSegment(o, d, tmax, Segment::kNoUnit, fan, nullptr, 0, apexes, bytes, s));
        // Derived, the direction lies on the octahedron and the length scales the other way.
        ASSERT_EQ(bytes[1] & packing::kDirectionMask, packing::kDirectionToApex);
        EXPECT_GE(double(s.length), tmax * (std::fabs(d[0]) + std::fabs(d[1]) + std::fabs(d[2])));
    }
}

TEST(SegmentPacking, SegmentsWrittenInFullReadBackAsMakeSegmentRoundsThemBesidePackedOnes) {
    std::mt19937_64 rng(5);
    PackedSamples record;
    // Samples of either form in one record, as a store that passes its threshold keeps.
    for (int i = 0; i < 200; ++i) record.Add(SampleRays(rng, record.apexes, i % 2 ? 1000.0 : 0.0), i % 3 != 0);
    record.ExpectReadBack("mixed");
    // A unit written in full takes any id.
    Segment s;
    const double o[3] = {1, 2, 3}, d[3] = {0, 0, 1};
    ASSERT_TRUE(MakeSegment(o, d, 1.0, s));
    s.unit = 7;
    const std::uint8_t fan = FanApexes::kLoose;
    std::vector<std::uint8_t> one;
    AppendInFull(&s, &fan, 1, one);
    ASSERT_EQ(one.size(), 34u);
    EXPECT_TRUE(RewritePackedUnit(one.data(), 123456 | Segment::kOpaqueBlocker));
    std::uint32_t unit;
    NextPacked(one.data(), unit);
    EXPECT_EQ(unit, 123456 | Segment::kOpaqueBlocker);
}

TEST(SegmentPacking, AStorePacksOnceItHoldsASixtyFourthOfItsBudgetOrTheBound) {
    // Budgets in whole MiB, as Frame_Coherence_Memory gives them.
    SampleStore small(4, std::size_t(8) << 20);
    EXPECT_FALSE(small.PackTightly());
    auto record = std::make_unique<BlockRecord>();
    record->packed.resize((std::size_t(8) << 20) / 64);
    ASSERT_TRUE(small.Put(0, std::move(record)));
    EXPECT_TRUE(small.PackTightly());
    small.Clear();
    EXPECT_FALSE(small.PackTightly());

    // A large budget packs from the bound on, not from a 64th of it.
    SampleStore large(4, std::size_t(1) << 40);
    auto big = std::make_unique<BlockRecord>();
    big->packed.resize(SampleStore::kFullSegmentsUpTo - (std::size_t(1) << 20));
    ASSERT_TRUE(large.Put(0, std::move(big)));
    EXPECT_FALSE(large.PackTightly());
    auto more = std::make_unique<BlockRecord>();
    more->packed.resize(std::size_t(2) << 20);
    ASSERT_TRUE(large.Put(1, std::move(more)));
    EXPECT_TRUE(large.PackTightly());
}

TEST(SegmentPacking, UnitsAreReadAndRewrittenWithinTheirWidth) {
    FanApexes apexes;
    std::vector<std::uint8_t> bytes;
    const double o[3] = {1, 2, 3}, d[3] = {1, 0, 0};
    Segment a, b, c;
    ASSERT_TRUE(PackSegment(o, d, 1.0, 5 | Segment::kOpaqueBlocker, FanApexes::kLoose, nullptr, 0, apexes, bytes, a));
    const std::size_t second = bytes.size();
    ASSERT_TRUE(PackSegment(o, d, 2.0, 70000, FanApexes::kLoose, &a, 1, apexes, bytes, b));
    const std::size_t third = bytes.size();
    ASSERT_TRUE(PackSegment(o, d, 3.0, Segment::kNoUnit, FanApexes::kLoose, &a, 2, apexes, bytes, c));
    std::uint32_t unit;
    const std::uint8_t *next = NextPacked(bytes.data(), unit);
    EXPECT_EQ(unit, 5 | Segment::kOpaqueBlocker);
    EXPECT_EQ(next, bytes.data() + second);
    next = NextPacked(next, unit);
    EXPECT_EQ(unit, 70000u);
    NextPacked(next, unit);
    EXPECT_EQ(unit, Segment::kNoUnit);
    // A short unit takes ids below 2^15 only; a long one any; none, nothing.
    EXPECT_TRUE(RewritePackedUnit(bytes.data(), 9 | Segment::kOpaqueBlocker));
    EXPECT_FALSE(RewritePackedUnit(bytes.data(), 40000 | Segment::kOpaqueBlocker));
    EXPECT_TRUE(RewritePackedUnit(bytes.data() + second, 123456));
    EXPECT_FALSE(RewritePackedUnit(bytes.data() + third, 1));
    std::vector<Segment> segments(3);
    std::vector<std::uint8_t> fanOf(3);
    ASSERT_TRUE(UnpackSample(bytes.data(), 3, apexes, segments.data(), fanOf.data()));
    EXPECT_EQ(segments[0].unit, 9 | Segment::kOpaqueBlocker);
    EXPECT_EQ(segments[1].unit, 123456u);
    EXPECT_EQ(segments[2].unit, Segment::kNoUnit);
}

TEST(SegmentPacking, BytesThatReferToAMissingApexDoNotUnpack) {
    FanApexes apexes;
    const double light[3] = {0, 50, 0};
    const std::uint8_t fan = apexes.AimFan(light);
    const double o[3] = {1, 0, 1}, d[3] = {-1 / std::sqrt(2502.0), 50 / std::sqrt(2502.0), -1 / std::sqrt(2502.0)};
    std::vector<std::uint8_t> bytes;
    Segment s;
    ASSERT_TRUE(PackSegment(o, d, std::sqrt(2502.0), Segment::kNoUnit, fan, nullptr, 0, apexes, bytes, s));
    ASSERT_EQ(bytes[1] & packing::kDirectionMask, packing::kDirectionToApex);
    Segment segment;
    std::uint8_t fanOf;
    EXPECT_TRUE(UnpackSample(bytes.data(), 1, apexes, &segment, &fanOf));
    FanApexes none;
    EXPECT_FALSE(UnpackSample(bytes.data(), 1, none, &segment, &fanOf));
}

TEST(SegmentPacking, RaysThatCannotBeStoredAppendNothing) {
    FanApexes apexes;
    std::vector<std::uint8_t> bytes;
    const double o[3] = {1, 2, NAN}, d[3] = {1, 0, 0};
    Segment s;
    EXPECT_FALSE(PackSegment(o, d, 1.0, Segment::kNoUnit, FanApexes::kLoose, nullptr, 0, apexes, bytes, s));
    EXPECT_TRUE(bytes.empty());
}

}  // namespace
