// Micro-benchmark (not a test): walker speed, Commit cost, dependency store size and
// DirtyPixels time.
//
// The "scene" is synthetic but shaped like a POV-Ray frame: a 64^3 grid over [-10,10]^3, a
// camera in front of it, a floor and a few spheres, lights outside the grid. Each pixel
// records its camera ray to the first hit and a shadow ray to the light (~80 voxels per
// pixel); the "heavy" run uses two lights and one mirror bounce off every surface (~150).
#include <malloc.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <random>
#include <thread>
#include <vector>

#include "povrayfc/change_set.h"
#include "povrayfc/dependency_store.h"
#include "povrayfc/segment_walker.h"

using namespace povrayfc;

namespace {

using Clock = std::chrono::steady_clock;

double Seconds(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); }

double Dot(const Vec3 &a, const Vec3 &b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec3 Normalize(const Vec3 &v) { return (1.0 / std::sqrt(Dot(v, v))) * v; }

struct Sphere {
    Vec3 c;
    double r;
};

const Sphere kSpheres[] = {{{-4, -2, 2}, 3}, {{3.5, -3, -1}, 2}, {{1, -1, 6}, 4}, {{6, -4, -6}, 1}};
const double kFloorY = -5;
const Vec3 kLight{25, 30, -25};
const Vec3 kLight2{-30, 20, 5};
const Vec3 kEye{0, 3, -22};
const int kW = 1920, kH = 1080;

// Nearest hit along o + t d, t > 1e-6; returns t (inf if none) and the normal.
double Trace(const Vec3 &o, const Vec3 &d, Vec3 &n) {
    double best = INFINITY;
    for (const Sphere &s : kSpheres) {
        Vec3 oc = o - s.c;
        double b = Dot(oc, d), c = Dot(oc, oc) - s.r * s.r, disc = b * b - c;
        if (disc < 0) continue;
        double t = -b - std::sqrt(disc);
        if (t < 1e-6) t = -b + std::sqrt(disc);
        if (t > 1e-6 && t < best) {
            best = t;
            n = Normalize(o + t * d - s.c);
        }
    }
    if (d.y < 0) {
        double t = (kFloorY - o.y) / d.y;
        if (t > 1e-6 && t < best) {
            best = t;
            n = Vec3{0, 1, 0};
        }
    }
    return best;
}

// Records the pixel's segments into rec: the camera ray to its first hit and a shadow ray
// to each light; with `heavy`, two lights and mirror rays (depth 2) off every surface.
void RecordPixel(const VoxelGrid &g, int px, int py, bool heavy, PixelRecorder &rec) {
    auto add = [&](std::uint32_t v) { rec.Add(v); };
    double fx = (px + 0.5) / kW * 2 - 1, fy = 1 - (py + 0.5) / kH * 2;
    Vec3 d = Normalize(Vec3{fx * 0.4 * kW / kH, fy * 0.4 - 0.2, 1});
    Vec3 o = kEye;
    for (int depth = 0; depth < (heavy ? 2 : 1); ++depth) {
        Vec3 n;
        double t = Trace(o, d, n);
        WalkSegment(g, o, d, 0, std::isinf(t) ? 2.0e10 : t, add);
        if (std::isinf(t)) return;
        Vec3 hit = o + t * d;
        WalkSegment(g, hit, kLight - hit, 1e-6, 1.0, add);  // shadow rays
        if (heavy) WalkSegment(g, hit, kLight2 - hit, 1e-6, 1.0, add);
        d = d - (2 * Dot(d, n)) * n;
        o = hit;
    }
}

std::size_t HeapInUse() { return mallinfo2().uordblks; }

// CPU time of the calling thread: the walker figures should not depend on other load.
double CpuSeconds() {
    timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

void BenchWalker(const VoxelGrid &g) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-1, 1);
    const int kRays = 400000;
    std::vector<Vec3> o(kRays), d(kRays);
    for (int i = 0; i < kRays; ++i) {
        o[i] = Vec3{9 * u(rng), 9 * u(rng), 9 * u(rng)};  // inside the grid, random directions
        d[i] = Vec3{u(rng), u(rng), u(rng)};
    }
    std::uint64_t voxels = 0, checksum = 0;
    double t0 = CpuSeconds();
    for (int i = 0; i < kRays; ++i)
        WalkSegment(g, o[i], d[i], 0, 2.0e10, [&](std::uint32_t v) {
            ++voxels;
            checksum += v;
        });
    double t1 = CpuSeconds();
    for (int i = 0; i < kRays; ++i) WalkSegment(g, o[i], d[i], 0, 0, [&](std::uint32_t v) { checksum += v; });
    double t2 = CpuSeconds();
    PixelRecorder rec;
    for (int i = 0; i < kRays; ++i) {
        if (i % 4 == 0) rec.Begin();  // ~4 rays per pixel
        WalkSegment(g, o[i], d[i], 0, 2.0e10, [&](std::uint32_t v) { rec.Add(v); });
        checksum += rec.Voxels().size();
    }
    double t3 = CpuSeconds();
    std::printf("walker: %d random rays from inside a %dx%dx%d grid to its edge, %.1f voxels/ray\n", kRays,
                g.Res(0), g.Res(1), g.Res(2), double(voxels) / kRays);
    std::printf("  walk                 %6.2f ns/voxel (%5.0f ns/ray, set-up included)\n",
                1e9 * (t1 - t0) / double(voxels), 1e9 * (t1 - t0) / kRays);
    std::printf("  set-up alone         %6.1f ns/ray (zero-length segments)\n", 1e9 * (t2 - t1) / kRays);
    std::printf("  walk + PixelRecorder %6.2f ns/voxel (checksum %llu)\n", 1e9 * (t3 - t2) / double(voxels),
                (unsigned long long)(checksum & 0xffff));
}

void BenchStore(const VoxelGrid &g, bool heavy, int threads) {
    std::printf("\nstore: %dx%d, %s, %d render thread(s)\n", kW, kH,
                heavy ? "camera ray, 2 shadow rays, mirror ray, its 2 shadow rays"
                      : "camera ray + 1 shadow ray",
                threads);
    std::size_t heap0 = HeapInUse();
    auto t0 = Clock::now();
    DependencyStore store(kW, kH);
    // Threads take interleaved 32-pixel-high bands, like POV-Ray's render blocks. Each
    // thread records kBatch pixels into kBatch recorders, then commits them, timing only
    // the Commit calls (thread CPU time, so other load on the machine matters less).
    const int kBatch = 64;
    std::vector<std::thread> pool;
    std::vector<double> commitSeconds(std::size_t(threads), 0.0);
    for (int ti = 0; ti < threads; ++ti)
        pool.emplace_back([&, ti] {
            std::vector<PixelRecorder> recs(kBatch);
            double commit = 0;
            for (int y0 = 32 * ti; y0 < kH; y0 += 32 * threads)
                for (int y = y0; y < std::min(kH, y0 + 32); ++y)
                    for (int x0 = 0; x0 < kW; x0 += kBatch) {
                        const int n = std::min(kBatch, kW - x0);
                        for (int i = 0; i < n; ++i) {
                            recs[std::size_t(i)].Begin();
                            RecordPixel(g, x0 + i, y, heavy, recs[std::size_t(i)]);
                        }
                        double c0 = CpuSeconds();
                        for (int i = 0; i < n; ++i) store.Commit(x0 + i, y, recs[std::size_t(i)]);
                        commit += CpuSeconds() - c0;
                    }
            commitSeconds[std::size_t(ti)] = commit;
        });
    for (std::thread &t : pool) t.join();
    auto t1 = Clock::now();
    double commitTotal = 0;
    for (double c : commitSeconds) commitTotal += c;
    std::size_t heap1 = HeapInUse();
    const double px = double(kW) * kH;
    std::size_t entries = store.EntryCount(), mem = store.MemoryBytes();
    std::size_t payload = mem - kW * std::size_t(kH) * sizeof(void *) - sizeof(store);
    std::printf("  trace+record+commit  %.2f s (%.0f ns/pixel incl. the toy tracer)\n", Seconds(t0, t1),
                1e9 * Seconds(t0, t1) / px * threads);
    std::printf("  Commit alone         %.0f ns/pixel, %.2f ns/entry (thread CPU time)\n", 1e9 * commitTotal / px,
                1e9 * commitTotal / double(entries));
    std::printf("  entries/pixel        %.1f\n", double(entries) / px);
    std::printf("  payload bytes/entry  %.3f\n", double(payload) / double(entries));
    std::printf("  MemoryBytes          %.1f MB = %.1f B/pixel (slots 8 B + blocks)\n", mem / 1e6, mem / px);
    std::printf("  heap in use (malloc) %.1f MB = %.1f B/pixel (incl. allocator overhead)\n", (heap1 - heap0) / 1e6,
                double(heap1 - heap0) / px);

    // Dirty sets: nothing; one voxel; a small object (4^3 voxels); a sphere-sized change.
    struct Case {
        const char *name;
        Box box;
        bool none;
    } cases[] = {
        {"no change", Box{}, true},
        {"1 voxel (on a sphere's front)", Box{{1.1, -1.1, 2.1}, {1.1, -1.1, 2.1}}, false},
        {"small object (~4^3 voxels)", Box{{5.5, -5, -7}, {6.5, -3, -5}}, false},
        {"sphere moved (~15^3 voxels)", Box{{-7, -5, -1}, {-1, 1, 5}}, false},
    };
    for (const Case &c : cases) {
        ChangeSet cs;
        if (!c.none) cs.AddBox(c.box);
        DirtyResult r = DirtyVoxels(g, cs);
        // 1 thread: best thread CPU time (robust to other load); 2 threads: best wall time.
        double best[2] = {1e9, 1e9};
        std::size_t dirty = 0;
        for (int i = 0; i < 3; ++i)
            for (int ti = 0; ti < 2; ++ti) {
                auto a = Clock::now();
                double c0 = CpuSeconds();
                DirtyMask m = store.DirtyPixels(r, ti + 1);
                double c1 = CpuSeconds();
                auto b = Clock::now();
                best[ti] = std::min(best[ti], ti == 0 ? c1 - c0 : Seconds(a, b));
                dirty = m.Count();
            }
        std::printf("  DirtyPixels %-28s %6.1f ms CPU (2 threads %6.1f ms wall)  %5zu dirty voxels -> %4.1f%% pixels\n",
                    c.name, 1e3 * best[0], 1e3 * best[1], r.voxels.Count(), 100.0 * double(dirty) / px);
    }
}

}  // namespace

int main() {
    VoxelGrid g(Box{{-10, -10, -10}, {10, 10, 10}}, 64, 64, 64);
    BenchWalker(g);
    BenchStore(g, false, 1);
    BenchStore(g, true, 2);
    return 0;
}
