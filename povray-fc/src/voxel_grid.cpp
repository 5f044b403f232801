// VoxelGrid construction (validation, padding, automatic resolution) and range queries.
#include "povrayfc/voxel_grid.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <stdexcept>
#include <string>

namespace povrayfc {

Box VoxelGrid::PaddedBounds(const Box &bounds) {
    if (bounds.HasNaN())
        throw std::invalid_argument("VoxelGrid: bounds contain NaN: " + ToString(bounds));
    if (!bounds.IsFinite())
        throw std::invalid_argument("VoxelGrid: bounds must be finite: " + ToString(bounds));
    if (bounds.Empty())
        throw std::invalid_argument("VoxelGrid: bounds are empty (lo > hi): " + ToString(bounds));
    double maxExtent = 0, maxAbs = 0;
    for (int a = 0; a < 3; ++a) {
        double e = bounds.hi[a] - bounds.lo[a];
        if (!std::isfinite(e))
            throw std::invalid_argument("VoxelGrid: bounds extent overflows: " + ToString(bounds));
        maxExtent = std::max(maxExtent, e);
        maxAbs = std::max({maxAbs, std::fabs(bounds.lo[a]), std::fabs(bounds.hi[a])});
    }
    // 1e-3 of the largest extent keeps flat axes from producing needle-thin cells; 1e-9 of
    // the coordinate magnitude keeps a padded width far above double rounding (~1e-16).
    double minExtent = std::max(1e-3 * maxExtent, 1e-9 * maxAbs);
    if (minExtent == 0) minExtent = 1.0;
    // Pad a hair beyond minExtent so padding an already padded box changes nothing
    // (its own 1e-9 * |coordinate| term grew by at most 5e-10 of minExtent).
    const double padTo = minExtent * (1 + 1e-6);
    Box padded = bounds;
    for (int a = 0; a < 3; ++a) {
        double e = bounds.hi[a] - bounds.lo[a];
        if (e < minExtent) {
            double mid = 0.5 * (bounds.lo[a] + bounds.hi[a]);
            padded.lo[a] = std::min(bounds.lo[a], mid - 0.5 * padTo);
            padded.hi[a] = std::max(bounds.hi[a], mid + 0.5 * padTo);
        }
    }
    return padded;
}

VoxelGrid::VoxelGrid(const Box &bounds, int nx, int ny, int nz) : bounds_(PaddedBounds(bounds)) {
    n_[0] = nx;
    n_[1] = ny;
    n_[2] = nz;
    std::uint64_t count = 1;
    for (int a = 0; a < 3; ++a) {
        if (n_[a] <= 0)
            throw std::invalid_argument("VoxelGrid: resolution must be positive, got " +
                                        std::to_string(n_[a]) + " on axis " + std::to_string(a));
        count *= std::uint64_t(n_[a]);
        if (count > kMaxVoxels)
            throw std::invalid_argument("VoxelGrid: " + std::to_string(nx) + "x" +
                                        std::to_string(ny) + "x" + std::to_string(nz) +
                                        " voxels exceed the limit of " + std::to_string(kMaxVoxels));
    }
    count_ = std::size_t(count);
    for (int a = 0; a < 3; ++a) {
        lo_[a] = bounds_.lo[a];
        w_[a] = (bounds_.hi[a] - bounds_.lo[a]) / n_[a];
        invW_[a] = 1.0 / w_[a];
        // Boundaries lo + k*w and positions derived from them carry a few ulps of the
        // coordinate magnitude in error; 32 ulps plus a 1e-7 cell covers that with room.
        double mag = std::max(std::fabs(bounds_.lo[a]), std::fabs(bounds_.hi[a]));
        margin_[a] = kRelativeMargin * w_[a] + 32 * DBL_EPSILON * mag;
    }
}

VoxelGrid VoxelGrid::Automatic(const Box &bounds, std::size_t targetVoxels) {
    if (targetVoxels == 0) throw std::invalid_argument("VoxelGrid::Automatic: targetVoxels must be > 0");
    Box b = PaddedBounds(bounds);
    const double cap = kMaxAutomaticResolution;
    double target = std::min(double(targetVoxels), cap * cap * cap);
    double e[3] = {b.hi.x - b.lo.x, b.hi.y - b.lo.y, b.hi.z - b.lo.z};
    int n[3] = {0, 0, 0};
    bool fixed[3] = {false, false, false};
    // Cubic cells of side s give prod(e/s) = target. An axis that would get fewer than 1
    // or more than `cap` cells is pinned and the budget is re-spread over the others, so
    // a flat or needle-like scene still gets about targetVoxels voxels.
    for (int iter = 0; iter < 4; ++iter) {
        double fixedProduct = 1, freeVolume = 1;
        int freeAxes = 0;
        for (int a = 0; a < 3; ++a) {
            if (fixed[a]) {
                fixedProduct *= n[a];
            } else {
                freeVolume *= e[a];
                ++freeAxes;
            }
        }
        if (freeAxes == 0) break;
        double remaining = std::max(1.0, target / fixedProduct);
        double s = std::pow(freeVolume / remaining, 1.0 / freeAxes);
        bool pinned = false;
        for (int a = 0; a < 3; ++a) {
            if (fixed[a]) continue;
            double raw = e[a] / s;
            if (raw < 1) {
                n[a] = 1;
                fixed[a] = pinned = true;
            } else if (raw > cap) {
                n[a] = int(cap);
                fixed[a] = pinned = true;
            } else {
                n[a] = int(std::lround(raw));
            }
        }
        if (!pinned) break;
    }
    for (int a = 0; a < 3; ++a) n[a] = std::clamp(n[a], 1, int(cap));
    return VoxelGrid(b, n[0], n[1], n[2]);
}

void VoxelGrid::Coords(std::uint32_t index, int &ix, int &iy, int &iz) const {
    if (index >= count_)
        throw std::invalid_argument("VoxelGrid::Coords: index " + std::to_string(index) +
                                    " out of range (voxel count " + std::to_string(count_) + ")");
    ix = int(index % std::uint32_t(n_[0]));
    index /= std::uint32_t(n_[0]);
    iy = int(index % std::uint32_t(n_[1]));
    iz = int(index / std::uint32_t(n_[1]));
}

Box VoxelGrid::VoxelBox(int ix, int iy, int iz) const {
    int i[3] = {ix, iy, iz};
    Box b;
    for (int a = 0; a < 3; ++a) {
        b.lo[a] = Boundary(a, i[a]);
        b.hi[a] = (i[a] + 1 == n_[a]) ? bounds_.hi[a] : Boundary(a, i[a] + 1);
    }
    return b;
}

bool VoxelGrid::BoxInside(const Box &b) const { return !b.HasNaN() && bounds_.Contains(b); }

bool VoxelGrid::VoxelRange(const Box &b, int first[3], int last[3]) const {
    if (b.Empty()) return false;  // also true for NaN boxes
    for (int a = 0; a < 3; ++a)
        if (!CellRange(a, b.lo[a], b.hi[a], margin_[a], first[a], last[a])) return false;
    return true;
}

}  // namespace povrayfc
