// Micro-benchmark of the fc engine's per-ray and per-frame costs (not a test).
//
//   povrayfc_bench [segments]
//
// Prints: the cost of recording one ray segment (what every traced ray pays with fc on),
// the cost of testing one stored segment against a frame's changes (what every stored
// segment pays once per coherent frame) for a local change and for many scattered
// changes, and the bytes a stored segment takes. Thread CPU time, median of 5 runs.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <random>
#include <vector>

#include "povrayfc/change_index.h"
#include "povrayfc/ray_recording.h"
#include "povrayfc/sample_store.h"

using namespace povrayfc;

namespace {

double ThreadSeconds() {
    timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

template <class F>
double MedianNs(std::size_t n, F f) {
    std::vector<double> runs;
    for (int r = 0; r < 5; ++r) {
        const double t0 = ThreadSeconds();
        f();
        runs.push_back((ThreadSeconds() - t0) * 1e9 / double(n));
    }
    std::sort(runs.begin(), runs.end());
    return runs[2];
}

struct Ray {
    double o[3], d[3], t;
};

// Camera-like rays from one eye into a 20-unit scene, half of them ending on something.
std::vector<Ray> SceneRays(std::size_t n) {
    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> u(-1, 1);
    std::vector<Ray> rays(n);
    for (Ray &r : rays) {
        r.o[0] = 0, r.o[1] = 2, r.o[2] = -20;
        r.d[0] = 0.5 * u(rng), r.d[1] = 0.4 * u(rng), r.d[2] = 1.0;
        r.t = u(rng) > 0 ? 2e10 : 20 + 10 * u(rng);
    }
    return rays;
}

}  // namespace

int main(int argc, char **argv) {
    const std::size_t n = argc > 1 ? std::size_t(std::atoll(argv[1])) : 2000000;
    const std::vector<Ray> rays = SceneRays(n);

    std::vector<Segment> segments;
    std::vector<std::uint8_t> fanOf;
    std::vector<std::uint8_t> packed;
    FanApexes apexes;
    segments.reserve(n);
    fanOf.reserve(n);
    SampleRecorder recorder;
    const double record = MedianNs(n, [&] {
        segments.clear();
        fanOf.clear();
        packed.clear();
        recorder.Begin(segments, fanOf, packed, apexes, nullptr, 0);
        StartRecordingRays(recorder);
        for (const Ray &r : rays) RecordRaySegment(r.o, r.d, r.t, kUnitNothing);
        StopRecordingRays();
    });
    std::printf("record a ray segment:            %6.2f ns\n", record);

    // A marble of radius 1 moving by 0.3: old and new position.
    std::vector<Hull> local;
    for (double x : {0.0, 0.3}) {
        Capsule c;
        c.a = c.b = Vec3{x, 1, 0};
        c.radius = 1;
        local.push_back(MakeHull(Box{Vec3{x - 1, 0, -1}, Vec3{x + 1, 2, 1}}, c));
    }
    std::mt19937_64 rng(2);
    std::uniform_real_distribution<double> u(-8, 8);
    std::vector<Hull> scattered;
    for (int i = 0; i < 500; ++i) {
        const Vec3 p{u(rng), u(rng) * 0.5 + 2, u(rng)};
        scattered.push_back(MakeHull(Box{p - Vec3{0.1, 0.1, 0.1}, p + Vec3{0.1, 0.1, 0.1}}));
    }
    for (auto *set : {&local, &scattered}) {
        const ChangeIndex index(*set);
        std::size_t hits = 0;
        const double query = MedianNs(n, [&] {
            hits = 0;
            for (const Segment &s : segments) hits += index.MayMeet(s);
        });
        std::printf("test a stored segment, %3zu hulls%s: %6.2f ns (%.1f%% may meet)\n", set->size(),
                    index.HasGrid() ? " (grid)" : "       ", query, 100.0 * double(hits) / double(n));
    }
    std::printf("stored segment:                  %6.2f bytes packed (%zu unpacked); stored sample: %zu bytes + its segments\n",
                double(packed.size()) / double(segments.size() ? segments.size() : 1), sizeof(Segment), sizeof(StoredSample));
    return 0;
}
