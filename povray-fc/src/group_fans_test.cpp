// Tests for GroupFans: a group's candidate hulls never leave out a hull that one of its
// samples' segments meets (built, and grown as a replayed block grows them), and groups
// leave out many samples that their block's cones alone would test.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "povrayfc/block_hulls.h"
#include "povrayfc/group_fans.h"
#include "povrayfc/ray_recording.h"
#include "povrayfc/sample_store.h"

using namespace povrayfc;

namespace {

Vec3 Normalised(Vec3 v) {
    const double n = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
    return (1.0 / n) * v;
}

// A camera over a floor (y = 0) under a light, with a mirror sphere in part of the view:
// a sample's camera ray hits the floor, the sphere or nothing; a floor hit tests the
// light and reflects (to the sky, or to the sphere); a sphere hit reflects anywhere, and
// its reflection's end tests the light too. Pixels (left..left+31, top..top+31) of a
// 320x240 view.
struct Scene {
    Vec3 eye{0.0, 6.0, -20.0}, light{-18.0, 30.0, -22.0}, ball{0.0, 3.0, 0.0};
    double ballRadius = 2.0;

    Vec3 Direction(double x, double y) const {
        return Normalised(Vec3{(x - 160.0) / 240.0, (120.0 - y) / 240.0 - 0.15, 1.0});
    }
    // Distance along (o, d) to the sphere, or -1.
    double HitBall(const Vec3 &o, const Vec3 &d) const {
        const Vec3 oc = o - ball;
        const double b = oc.x * d.x + oc.y * d.y + oc.z * d.z;
        const double c = oc.x * oc.x + oc.y * oc.y + oc.z * oc.z - ballRadius * ballRadius;
        const double disc = b * b - c;
        if (disc < 0) return -1;
        const double t = -b - std::sqrt(disc);
        return t > 1e-6 ? t : -1;
    }
};

void Shadow(const Scene &scene, const Vec3 &p) {
    const Vec3 toLight = scene.light - p;
    const double dist = std::sqrt(toLight.x * toLight.x + toLight.y * toLight.y + toLight.z * toLight.z);
    const Vec3 l = (1.0 / dist) * toLight;
    const double po[3] = {p.x, p.y, p.z}, ld[3] = {l.x, l.y, l.z};
    ShadowSegmentRecord shadow(po, ld, dist);
}

void TraceSample(const Scene &scene, double x, double y, std::mt19937_64 &rng) {
    std::uniform_real_distribution<double> u(-1, 1);
    const Vec3 d = scene.Direction(x, y);
    const double o[3] = {scene.eye.x, scene.eye.y, scene.eye.z}, dd[3] = {d.x, d.y, d.z};
    const double tBall = scene.HitBall(scene.eye, d);
    const double tFloor = d.y < 0 ? -scene.eye.y / d.y : -1;
    if (tBall > 0 && (tFloor < 0 || tBall < tFloor)) {
        RecordRaySegment(o, dd, tBall, kUnitNothing);
        const Vec3 p = scene.eye + tBall * d;
        Shadow(scene, p);
        // A curved mirror: its reflections go anywhere, some to the floor.
        const Vec3 r = Normalised(Vec3{u(rng), u(rng), u(rng)});
        const double po[3] = {p.x, p.y, p.z}, rd[3] = {r.x, r.y, r.z};
        if (r.y < 0) {
            const double t = -p.y / r.y;
            RecordRaySegment(po, rd, t, kUnitNothing);
            Shadow(scene, p + t * r);
        } else {
            RecordRaySegment(po, rd, 2e10, kUnitNothing);
        }
    } else if (tFloor > 0) {
        RecordRaySegment(o, dd, tFloor, kUnitNothing);
        const Vec3 p = scene.eye + tFloor * d;
        Shadow(scene, p);
        const Vec3 r{d.x, -d.y, d.z};  // a flat mirror: reflections of the sky or the ball
        const double po[3] = {p.x, p.y, p.z}, rd[3] = {r.x, r.y, r.z};
        const double t = scene.HitBall(p, r);
        RecordRaySegment(po, rd, t > 0 ? t : 2e10, kUnitNothing);
    } else {
        RecordRaySegment(o, dd, 2e10, kUnitNothing);
    }
}

// The block at (left, top), every pixel one sample, recorded as the hooks record them.
BlockRecord RecordBlock(const Scene &scene, int left, int top, std::mt19937_64 &rng) {
    BlockRecord record;
    record.left = left;
    record.top = top;
    record.right = left + 31;
    record.bottom = top + 31;
    SampleRecorder recorder;
    std::vector<Segment> segments;
    std::vector<std::uint8_t> fanOf;
    for (int y = top; y <= record.bottom; ++y)
        for (int x = left; x <= record.right; ++x) {
            recorder.Begin(segments, fanOf, record.packed, record.apexes, nullptr, 0);
            StartRecordingRays(recorder);
            TraceSample(scene, x, y, rng);
            StopRecordingRays();
            StoredSample s;
            s.x = x;
            s.y = y;
            s.group = std::uint32_t(record.GroupOf(x, y));
            s.firstByte = std::uint32_t(recorder.FirstByte());
            s.segmentCount = std::uint32_t(recorder.Count());
            record.samples.push_back(s);
        }
    BuildRecordFans(record);
    return record;
}

// Hulls as a moving object leaves them: a few boxes and capsules somewhere in the room.
std::vector<Hull> SomeHulls(std::mt19937_64 &rng) {
    std::uniform_real_distribution<double> x(-15, 15), y(0, 12), z(-8, 20), size(0.1, 2);
    std::vector<Hull> hulls;
    for (int i = 0; i < 4; ++i) {
        const Vec3 c{x(rng), y(rng), z(rng)};
        const double s = size(rng);
        const Box box{c - Vec3{s, s, s}, c + Vec3{s, s, s}};
        hulls.push_back(i % 2 ? MakeHull(box) : MakeHull(box, Capsule{c - Vec3{s, s, s}, c + Vec3{s, s, s}, 0.1}));
    }
    return hulls;
}

struct Counts {
    long checkedSegments = 0, samplesInReachedBlocks = 0, samplesInReachedGroups = 0;
};

// Invariant: every segment that meets a hull is claimed by its group's candidates.
void CheckGroups(const BlockRecord &record, const ChangeIndex &changes, Counts &counts) {
    const BlockHulls block = FindBlockHulls(record.fans, changes);
    ASSERT_EQ(record.groupFans.size(), record.GroupCount());
    for (const StoredSample &s : record.samples) {
        const std::size_t g = record.GroupOf(s.x, s.y);
        const BlockHulls group = FindGroupHulls(record.groupFans[g], changes, block);
        counts.samplesInReachedBlocks += block.Any();
        counts.samplesInReachedGroups += group.Any();
        std::vector<Segment> segments(s.segmentCount);
        std::vector<std::uint8_t> fanOf(s.segmentCount);
        ASSERT_TRUE(record.Unpack(s, segments.data(), fanOf.data()));
        for (std::uint32_t i = 0; i < s.segmentCount; ++i) {
            bool meets = false;
            for (const Hull &h : changes.Hulls()) meets |= MayMeet(segments[i], h);
            if (!meets) continue;
            ++counts.checkedSegments;
            ASSERT_TRUE(group.SegmentMayMeet(segments[i], fanOf[i], changes))
                << "block " << record.left << "," << record.top << " sample " << s.x << "," << s.y << " segment " << i;
        }
    }
}

TEST(GroupFans, NeverLeaveOutAHullASampleMeets) {
    std::mt19937_64 rng(41);
    const Scene scene;
    Counts counts;
    for (int top = 0; top < 240; top += 32)
        for (int left = 0; left < 320; left += 32) {
            const BlockRecord record = RecordBlock(scene, left, top, rng);
            for (int k = 0; k < 6; ++k) {
                const ChangeIndex changes(SomeHulls(rng));
                CheckGroups(record, changes, counts);
                if (HasFatalFailure()) return;
            }
        }
    EXPECT_GT(counts.checkedSegments, 5000);
    // The point of the groups: far fewer samples left to test one by one.
    EXPECT_LT(counts.samplesInReachedGroups, counts.samplesInReachedBlocks * 3 / 4);
}

TEST(GroupFans, GrownGroupsHoldTheSamplesTracedAnew) {
    std::mt19937_64 rng(43);
    const Scene scene;
    Counts counts;
    for (int block = 0; block < 20; ++block) {
        const int left = 32 * int(rng() % 10), top = 32 * int(rng() % 7);
        BlockRecord record = RecordBlock(scene, left, top, rng);
        // Some samples traced anew, as a replayed block traces its dirty samples, after
        // the ball moved: their rays are packed onto the record's end and the samples point at
        // them.
        Scene moved;
        moved.ball = Vec3{-4.0, 2.5, -6.0};
        moved.ballRadius = 3.0;
        std::vector<std::pair<std::size_t, std::size_t>> added;
        std::vector<std::uint32_t> addedGroup;
        SampleRecorder recorder;
        std::vector<Segment> traced;
        std::vector<std::uint8_t> tracedFans;
        for (StoredSample &s : record.samples) {
            if (rng() % 4) continue;
            recorder.Begin(traced, tracedFans, record.packed, record.apexes, nullptr, 0);
            StartRecordingRays(recorder);
            TraceSample(moved, s.x, s.y, rng);
            StopRecordingRays();
            s.firstByte = std::uint32_t(recorder.FirstByte());
            s.segmentCount = std::uint32_t(recorder.Count());
            added.emplace_back(recorder.First(), recorder.Count());
            addedGroup.push_back(s.group);
        }
        GrowRecordFans(record, traced.data(), tracedFans.data(), added, addedGroup);
        for (int k = 0; k < 10; ++k) {
            CheckGroups(record, ChangeIndex(SomeHulls(rng)), counts);
            if (HasFatalFailure()) return;
        }
    }
    EXPECT_GT(counts.checkedSegments, 1000);
}

// A sample of `record` at pixel (x, y) whose segments (one each) ended on `units`
// (Segment::kNoUnit for none).
void AddSampleEndingOn(BlockRecord &record, int x, int y, const std::vector<std::uint32_t> &units) {
    StoredSample s;
    s.x = x;
    s.y = y;
    s.group = std::uint32_t(record.GroupOf(x, y));
    s.firstByte = std::uint32_t(record.packed.size());
    std::vector<Segment> earlier;
    for (std::size_t k = 0; k < units.size(); ++k) {
        const double o[3] = {double(x), double(y), -10.0 + double(k)}, d[3] = {0.0, 0.0, 1.0};
        Segment packed;
        ASSERT_TRUE(PackSegment(o, d, 20.0, units[k], FanApexes::kLoose, earlier.data(), earlier.size(),
                                record.apexes, record.packed, packed));
        earlier.push_back(packed);
    }
    s.segmentCount = std::uint32_t(units.size());
    record.samples.push_back(s);
}

// An empty record of a 16 x 16 block: 2 x 2 groups.
BlockRecord FourGroupBlock() {
    BlockRecord record;
    record.right = 15;
    record.bottom = 15;
    return record;
}

TEST(GroupIndex, EachGroupListsItsSamplesAndHoldsWhatTheyHold) {
    // Invariant: a group's flags and unit mask hold every sample's of the group (Begin
    // passes over a group whose don't concern the frame), and every sample is listed once,
    // under its group.
    BlockRecord record = FourGroupBlock();
    AddSampleEndingOn(record, 1, 1, {3, Segment::kNoUnit});
    AddSampleEndingOn(record, 9, 2, {5, 7 | Segment::kOpaqueBlocker});
    AddSampleEndingOn(record, 2, 9, {40000});
    AddSampleEndingOn(record, 10, 10, {});
    AddSampleEndingOn(record, 3, 3, {4});
    record.samples[3].segmentCount = StoredSample::kEverything;
    record.samples[2].orderSensitive = 1;
    BuildGroupIndex(record);

    const GroupIndex &index = record.groupIndex;
    ASSERT_EQ(index.start.size(), 5u);  // 4 groups and the end
    std::vector<int> listed(record.samples.size(), 0);
    for (std::size_t g = 0; g < 4; ++g)
        for (std::uint32_t k = index.Begin(g); k < index.End(g); ++k) {
            ++listed[index.samples[k]];
            EXPECT_EQ(record.samples[index.samples[k]].group, g);
        }
    EXPECT_EQ(listed, std::vector<int>(record.samples.size(), 1));
    EXPECT_EQ(index.unitMask[0], UnitMaskBit(3) | UnitMaskBit(4));
    EXPECT_EQ(index.unitMask[1], UnitMaskBit(5) | UnitMaskBit(7));
    EXPECT_EQ(index.unitMask[2], UnitMaskBit(40000));
    EXPECT_EQ(index.unitMask[3], 0u);
    EXPECT_EQ(index.flags[0], 0);
    EXPECT_EQ(index.flags[1], GroupIndex::kOpaqueBlockerTest);
    EXPECT_EQ(index.flags[2], GroupIndex::kOrderSensitive);
    EXPECT_EQ(index.flags[3], GroupIndex::kEverything);

    // A sample traced again in place adds what it holds now; nothing is taken out.
    AddSampleEndingOn(record, 1, 2, {6 | Segment::kOpaqueBlocker});
    record.samples[0] = record.samples.back();
    record.samples.pop_back();
    AddToGroupIndex(record, record.samples[0]);
    EXPECT_EQ(index.unitMask[0], UnitMaskBit(3) | UnitMaskBit(4) | UnitMaskBit(6));
    EXPECT_EQ(index.flags[0], GroupIndex::kOpaqueBlockerTest);
}

TEST(GroupIndex, ARecordBuiltFromAnOldOneCarriesWhatItsKeptSamplesHeld) {
    // A replayed block whose samples came in another order gets a new record: the samples
    // kept from the old one are not read again, their groups' masks and blocker flags
    // carry over; the traced ones are read. The cones' build reads every segment anew.
    BlockRecord old = FourGroupBlock();
    AddSampleEndingOn(old, 1, 1, {3, Segment::kNoUnit});
    AddSampleEndingOn(old, 9, 2, {5, 7 | Segment::kOpaqueBlocker});
    AddSampleEndingOn(old, 2, 9, {8});
    BuildGroupIndex(old);

    BlockRecord record = FourGroupBlock();
    AddSampleEndingOn(record, 9, 2, {5, 7 | Segment::kOpaqueBlocker});  // kept
    AddSampleEndingOn(record, 2, 9, {40000});                            // traced anew
    AddSampleEndingOn(record, 1, 1, {3, Segment::kNoUnit});              // kept
    const std::vector<std::uint8_t> kept = {1, 0, 1};
    BuildGroupIndex(record, &old.groupIndex, &kept);
    const GroupIndex &index = record.groupIndex;
    EXPECT_EQ(index.unitMask[0], UnitMaskBit(3));
    EXPECT_EQ(index.unitMask[1], UnitMaskBit(5) | UnitMaskBit(7));
    EXPECT_EQ(index.unitMask[2], UnitMaskBit(8) | UnitMaskBit(40000));  // a superset
    EXPECT_EQ(index.flags[1], GroupIndex::kOpaqueBlockerTest);
    EXPECT_EQ(index.flags[0] | index.flags[2] | index.flags[3], 0);

    BuildRecordFans(record);
    EXPECT_EQ(index.unitMask[0], UnitMaskBit(3));
    EXPECT_EQ(index.unitMask[1], UnitMaskBit(5) | UnitMaskBit(7));
    EXPECT_EQ(index.unitMask[2], UnitMaskBit(40000));  // exact again
    EXPECT_EQ(index.flags[1], GroupIndex::kOpaqueBlockerTest);
    EXPECT_EQ(index.flags[0] | index.flags[2] | index.flags[3], 0);
    EXPECT_EQ(record.unitMask, UnitMaskBit(3) | UnitMaskBit(5) | UnitMaskBit(7) | UnitMaskBit(40000));
}

TEST(GroupFans, GroupOfFollowsTheNearestPixelInsideTheBlock) {
    BlockRecord record;
    record.left = 64;
    record.top = 32;
    record.right = 64 + 19;  // an edge block 20 x 12: groups 3 x 2
    record.bottom = 32 + 11;
    EXPECT_EQ(record.GroupCount(), 6u);
    EXPECT_EQ(record.GroupOf(64, 32), 0u);
    EXPECT_EQ(record.GroupOf(71.4, 39.4), 0u);
    EXPECT_EQ(record.GroupOf(71.6, 32), 1u);   // nearest pixel 72
    EXPECT_EQ(record.GroupOf(63.0, 31.0), 0u); // AA method 1's row above and column left
    EXPECT_EQ(record.GroupOf(83.0, 43.0), 5u);
    EXPECT_EQ(record.GroupOf(90.0, 50.0), 5u);  // clamped into the block
}

}  // namespace
