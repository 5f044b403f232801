// ChangeDrift: a frame's changes never reach farther beyond an earlier frame's than Since()
// says, and only the last kFrames stamped frames are known.
#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "povrayfc/change_drift.h"

using namespace povrayfc;

namespace {

const double kInf = std::numeric_limits<double>::infinity();

// How far p lies outside b along any axis (0 inside).
double Outside(const Vec3 &p, const Box &b) {
    double out = 0;
    for (int a = 0; a < 3; ++a) out = std::max({out, b.lo[a] - p[a], p[a] - b.hi[a]});
    return out;
}

TEST(ChangeDrift, EveryPointOfTheNewBoxLiesWithinTheDriftOfTheOld) {
    std::mt19937_64 rng(23);
    std::uniform_real_distribution<double> pos(-20, 20), size(0.01, 8), unit(0, 1);
    for (int i = 0; i < 20000; ++i) {
        const Vec3 lo{pos(rng), pos(rng), pos(rng)};
        const Box then{lo, lo + Vec3{size(rng), size(rng), size(rng)}};
        const Vec3 shift = (i % 4 == 0) ? Vec3{0, 0, 0} : 0.05 * Vec3{pos(rng), pos(rng), pos(rng)};
        const Box now{then.lo + shift, then.hi + shift + double(i % 3) * Vec3{unit(rng), 0, unit(rng)}};
        const double drift = DriftBeyond(now, then);
        ASSERT_GE(drift, 0.0);
        for (int k = 0; k < 8; ++k) {
            const Vec3 corner{(k & 1) ? now.hi.x : now.lo.x, (k & 2) ? now.hi.y : now.lo.y, (k & 4) ? now.hi.z : now.lo.z};
            ASSERT_LE(Outside(corner, then), drift) << i;
        }
    }
    // A box inside the other drifts only by the margins' hair; the same box by none.
    const Box big{Vec3{0, 0, 0}, Vec3{4, 4, 4}}, small{Vec3{1, 1, 1}, Vec3{2, 2, 2}};
    EXPECT_LT(DriftBeyond(small, big), 1e-4);
    EXPECT_EQ(DriftBeyond(big, big), 0.0);
    EXPECT_NEAR(DriftBeyond(Box{Vec3{0, 0, 0}, Vec3{4, 4, 5}}, big), 1.0, 1e-4);
}

TEST(ChangeDrift, KnowsTheLastFramesOnly) {
    ChangeDrift drift;
    EXPECT_EQ(drift.Since(0), kInf);
    const Box first{Vec3{0, 0, 0}, Vec3{1, 1, 1}};
    const std::uint32_t a = drift.Begin(first);
    EXPECT_NE(a, 0u);
    EXPECT_EQ(drift.Since(a), 0.0);
    const Box second{Vec3{0.5, 0, 0}, Vec3{1.5, 1, 1}};
    const std::uint32_t b = drift.Begin(second);
    EXPECT_GT(b, a);
    EXPECT_EQ(drift.Since(a), DriftBeyond(second, first));
    EXPECT_EQ(drift.Since(b), 0.0);
    EXPECT_EQ(drift.Since(b + 1), kInf);  // not yet stamped
    for (std::uint32_t i = 0; i < ChangeDrift::kFrames - 1; ++i) drift.Begin(second);
    EXPECT_EQ(drift.Since(a), kInf);  // fell out of the ring
    EXPECT_EQ(drift.Since(b), 0.0);   // the same box since
}

}  // namespace
