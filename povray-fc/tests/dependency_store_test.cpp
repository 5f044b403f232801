// Tests for PixelRecorder and DependencyStore: dedupe, round trips, dirty pixels, threads, size.
#include <algorithm>
#include <random>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "povrayfc/dependency_store.h"
#include "povrayfc/segment_walker.h"

using namespace povrayfc;

namespace {

// The pixel's voxels, sorted: ForEachVoxel promises no order, so tests compare sets (a
// duplicate would still show up as an extra element).
std::vector<std::uint32_t> Stored(const DependencyStore &s, int x, int y) {
    std::vector<std::uint32_t> v;
    s.ForEachVoxel(x, y, [&](std::uint32_t id) { v.push_back(id); });
    std::sort(v.begin(), v.end());
    return v;
}

void Record(PixelRecorder &r, std::initializer_list<std::uint32_t> ids) {
    r.Begin();
    for (std::uint32_t id : ids) r.Add(id);
}

}  // namespace

TEST(PixelRecorder, KeepsUniqueVoxelsAndBeginForgets) {
    PixelRecorder r;
    Record(r, {5, 5, 5, 9, 5, 1, 9, 1, 7});
    std::vector<std::uint32_t> got = r.Voxels();
    // Repeats, adjacent or not, are recorded once, in first-seen order.
    EXPECT_EQ(got, (std::vector<std::uint32_t>{5, 9, 1, 7}));
    // SortedVoxels sorts the unique ids.
    EXPECT_EQ(r.SortedVoxels(), (std::vector<std::uint32_t>{1, 5, 7, 9}));
    r.MarkEverything();
    r.Begin();
    // Begin forgets the previous pixel's voxels and its "everything" mark.
    EXPECT_TRUE(r.Voxels().empty());
    EXPECT_FALSE(r.Everything());
    r.Add(5);
    // A voxel from the previous pixel is recorded again for the new one.
    EXPECT_EQ(r.Voxels(), std::vector<std::uint32_t>{5});
}

TEST(PixelRecorder, DedupesThousandsOfVoxelsThroughGrowth) {
    PixelRecorder r;
    std::mt19937 rng(3);
    for (int pixel = 0; pixel < 20; ++pixel) {
        r.Begin();
        std::set<std::uint32_t> want;
        int n = 10 + int(rng() % 5000);
        for (int i = 0; i < n; ++i) {
            std::uint32_t v = rng() % 3000;
            want.insert(v);
            r.Add(v);
        }
        std::vector<std::uint32_t> got = r.SortedVoxels();
        // Exactly the distinct ids survive, also after the hash table grew.
        ASSERT_EQ(got, std::vector<std::uint32_t>(want.begin(), want.end())) << pixel;
    }
}

TEST(DependencyStore, CommitReplaceClearAndHas) {
    DependencyStore s(4, 3);
    PixelRecorder r;
    // A fresh store has no list for any pixel.
    EXPECT_FALSE(s.Has(0, 0));
    Record(r, {40000, 3, 70000, 3, 0});
    s.Commit(2, 1, r);
    // A committed pixel has exactly its unique ids.
    EXPECT_TRUE(s.Has(2, 1));
    EXPECT_EQ(Stored(s, 2, 1), (std::vector<std::uint32_t>{0, 3, 40000, 70000}));
    // Commit does not reorder (sort) the recorder's list.
    EXPECT_EQ(r.Voxels(), (std::vector<std::uint32_t>{40000, 3, 70000, 0}));
    EXPECT_EQ(s.VoxelCountAt(2, 1), 4u);
    // Neighbouring pixels are untouched.
    EXPECT_FALSE(s.Has(1, 1));
    EXPECT_FALSE(s.Has(2, 0));
    Record(r, {8});
    s.Commit(2, 1, r);
    // Committing again replaces the list.
    EXPECT_EQ(Stored(s, 2, 1), std::vector<std::uint32_t>{8});
    r.Begin();
    s.Commit(3, 2, r);
    // A pixel whose rays met no voxel has an (empty) list: it is known to depend on nothing.
    EXPECT_TRUE(s.Has(3, 2));
    EXPECT_TRUE(Stored(s, 3, 2).empty());
    s.Clear(2, 1);
    // Clear forgets the pixel.
    EXPECT_FALSE(s.Has(2, 1));
    EXPECT_TRUE(Stored(s, 2, 1).empty());
    // Pixels outside the image are rejected.
    EXPECT_THROW(s.Commit(4, 0, r), std::invalid_argument);
    EXPECT_THROW(s.Clear(0, -1), std::invalid_argument);
    EXPECT_THROW(s.Has(0, 3), std::invalid_argument);
    // Bad image sizes are rejected.
    EXPECT_THROW(DependencyStore(0, 5), std::invalid_argument);
    EXPECT_THROW(DependencyStore(70000, 70000), std::invalid_argument);
}

TEST(DependencyStore, DirtyPixelsFollowsDependencies) {
    DependencyStore s(3, 2);
    PixelRecorder r;
    Record(r, {1, 2, 3});
    s.Commit(0, 0, r);
    Record(r, {3, 4});
    s.Commit(1, 0, r);
    Record(r, {7});
    s.Commit(2, 0, r);
    r.Begin();
    s.Commit(0, 1, r);  // empty list
    r.Begin();
    r.Add(5);
    r.MarkEverything();
    s.Commit(1, 1, r);  // depends on everything
    // (2, 1) never committed.

    VoxelSet none(10);
    DirtyMask m0 = s.DirtyPixels(none);
    // With nothing changed only the never-rendered pixel is dirty.
    EXPECT_EQ(m0.Count(), 1u);
    EXPECT_TRUE(m0.Test(2, 1));

    VoxelSet d(10);
    d.Set(3);
    DirtyMask m = s.DirtyPixels(d);
    // Pixels whose lists contain the dirty voxel are dirty.
    EXPECT_TRUE(m.Test(0, 0));
    EXPECT_TRUE(m.Test(1, 0));
    // A pixel with other voxels only is clean.
    EXPECT_FALSE(m.Test(2, 0));
    // A pixel that met no voxel is clean for a local change.
    EXPECT_FALSE(m.Test(0, 1));
    // An "everything" pixel is dirty as soon as anything changed.
    EXPECT_TRUE(m.Test(1, 1));
    EXPECT_TRUE(s.DependsOnEverything(1, 1));
    // A never-committed pixel is always dirty.
    EXPECT_TRUE(m.Test(2, 1));
    EXPECT_EQ(m.Count(), 4u);

    VoxelSet small(5);
    small.Set(0);
    DirtyMask ms = s.DirtyPixels(small);
    // A recorded id the dirty set does not cover (7 >= 5: another grid?) counts as dirty.
    EXPECT_TRUE(ms.Test(2, 0));
    EXPECT_FALSE(ms.Test(1, 0));

    DirtyResult all;
    all.voxels = VoxelSet(10);
    all.all = true;
    // An "everything changed" result dirties every pixel, also those that met no voxel.
    EXPECT_EQ(s.DirtyPixels(all).Count(), 6u);
    // Splitting the work over threads gives the same mask.
    DirtyMask m2 = s.DirtyPixels(d, 2), m8 = s.DirtyPixels(d, 8);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 3; ++x) {
            EXPECT_EQ(m2.Test(x, y), m.Test(x, y));
            EXPECT_EQ(m8.Test(x, y), m.Test(x, y));
        }
}

TEST(DependencyStore, ConcurrentCommitsOfDistinctPixels) {
    const int W = 97, H = 61, kThreads = 4;
    DependencyStore s(W, H);
    auto idsFor = [](int x, int y, int round) {
        std::vector<std::uint32_t> v;
        // Unique ids in no particular order (k -> k * 7919 mod 64 is one-to-one).
        for (int k = 0; k < 1 + (x * 7 + y * 3 + round) % 40; ++k)
            v.push_back(std::uint32_t((x + 1) * 1000 + y * 37 + (k * 7919 % 64) * (round + 1)));
        return v;
    };
    // Each thread owns every kThreads-th pixel and commits it several times (replacing).
    std::vector<std::thread> pool;
    for (int t = 0; t < kThreads; ++t)
        pool.emplace_back([&, t] {
            PixelRecorder r;
            for (int round = 0; round < 3; ++round)
                for (int i = t; i < W * H; i += kThreads) {
                    r.Begin();
                    for (std::uint32_t v : idsFor(i % W, i / W, round)) r.Add(v);
                    s.Commit(i % W, i / W, r);
                }
        });
    for (std::thread &t : pool) t.join();
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            std::vector<std::uint32_t> want = idsFor(x, y, 2);
            std::sort(want.begin(), want.end());
            want.erase(std::unique(want.begin(), want.end()), want.end());
            // Every pixel holds exactly its last committed list.
            ASSERT_EQ(Stored(s, x, y), want) << x << "," << y;
        }
}

TEST(DependencyStore, RealisticPixelsCostUnderTwoBytesPerEntry) {
    // ~60 voxels per pixel: a camera ray and a shadow ray through a 64^3 grid.
    VoxelGrid g(Box{{-10, -10, -10}, {10, 10, 10}}, 64, 64, 64);
    const int W = 64, H = 48;
    DependencyStore s(W, H);
    PixelRecorder r;
    std::vector<std::set<std::uint32_t>> want(std::size_t(W) * H);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            r.Begin();
            Vec3 eye{0, 0, -30}, dir{(x - W / 2) / 80.0, (y - H / 2) / 80.0, 1};
            double tHit = 25 + 10.0 * ((x * 13 + y * 7) % 17) / 17;
            std::set<std::uint32_t> &w = want[std::size_t(y) * W + std::size_t(x)];
            auto add = [&](std::uint32_t v) {
                r.Add(v);
                w.insert(v);
            };
            WalkSegment(g, eye, dir, 0, tHit, add);
            Vec3 hit = eye + tHit * dir;
            WalkSegment(g, hit, Vec3{30, 30, -30} - hit, 0, 1, add);
            s.Commit(x, y, r);
        }
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const std::set<std::uint32_t> &w = want[std::size_t(y) * W + std::size_t(x)];
            // Each pixel holds exactly the set of voxels its rays walked.
            ASSERT_EQ(Stored(s, x, y), std::vector<std::uint32_t>(w.begin(), w.end())) << x << "," << y;
        }
    double entries = double(s.EntryCount());
    double payload = double(s.MemoryBytes() - sizeof(s) - std::size_t(W) * H * sizeof(void *));
    // The rays touch a realistic number of voxels per pixel.
    EXPECT_GT(entries / (W * H), 40);
    // Encoded lists cost at most ~2 bytes per voxel entry (headers and padding included).
    EXPECT_LT(payload / entries, 2.0) << payload / entries;
    // Every pixel with voxels owns one block.
    EXPECT_EQ(s.BlockCount(), std::size_t(W) * H);
    DependencyStore moved = std::move(s);
    // Moving a store keeps its lists.
    EXPECT_EQ(double(moved.EntryCount()), entries);
    moved.ClearAll();
    // ClearAll forgets every pixel.
    EXPECT_FALSE(moved.Has(0, 0));
    EXPECT_EQ(moved.BlockCount(), 0u);
}

TEST(DependencyStore, EndToEndMovingObjectDirtiesOnlyPixelsSeeingIt) {
    // Orthographic camera looking down -z at a 16^3 grid; each pixel's ray covers one column.
    VoxelGrid g(Box{{0, 0, 0}, {16, 16, 16}}, 16, 16, 16);
    DependencyStore s(16, 16);
    PixelRecorder r;
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) {
            r.Begin();
            WalkSegment(g, Vec3{x + 0.5, y + 0.5, 20}, Vec3{0, 0, -1}, 0, 2.0e10,
                        [&](std::uint32_t v) { r.Add(v); });
            s.Commit(x, y, r);
        }
    ChangeSet cs;
    cs.AddBox(Box{{4.2, 6.2, 3}, {5.8, 6.8, 4}});  // inside columns x=4..5, y=6
    DirtyResult d = DirtyVoxels(g, cs);
    DirtyMask m = s.DirtyPixels(d);
    // Exactly the pixels whose columns contain the change are dirty.
    EXPECT_EQ(m.Count(), 2u);
    EXPECT_TRUE(m.Test(4, 6));
    EXPECT_TRUE(m.Test(5, 6));
}
