// ChangeDrift: the stamps of recent frames and how far the current changes drifted since.
#include "povrayfc/change_drift.h"

#include <algorithm>
#include <cmath>

namespace povrayfc {

double DriftBeyond(const Box &now, const Box &then) {
    double out = 0.0, centres = 0.0, halves = 0.0;
    for (int a = 0; a < 3; ++a) {
        out = std::max({out, now.hi[a] - then.hi[a], then.lo[a] - now.lo[a]});
        centres = std::max(centres, std::fabs(0.5 * (now.lo[a] + now.hi[a]) - 0.5 * (then.lo[a] + then.hi[a])));
    }
    const Vec3 en = now.Extent(), et = then.Extent();
    halves = std::fabs(0.5 * std::max({en.x, en.y, en.z}) - 0.5 * std::max({et.x, et.y, et.z}));
    // A hair more for this arithmetic's own rounding.
    return (out + 0x1p-18 * (centres + halves)) * (1.0 + 0x1p-40);
}

std::uint32_t ChangeDrift::Begin(const Box &bounds) {
    if (last_ == std::numeric_limits<std::uint32_t>::max()) return 0;
    const std::uint32_t stamp = ++last_;
    for (Frame &f : frames_)
        if (f.stamp != 0) f.drift = DriftBeyond(bounds, f.bounds);
    Frame &self = frames_[stamp % kFrames];
    self.stamp = stamp;
    self.bounds = bounds;
    self.drift = 0.0;
    return stamp;
}

}  // namespace povrayfc
