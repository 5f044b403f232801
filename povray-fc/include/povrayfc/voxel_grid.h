// Uniform voxel grid over a finite box: index layout, cell boundaries and box-to-voxel queries.
#ifndef POVRAYFC_VOXEL_GRID_H
#define POVRAYFC_VOXEL_GRID_H

#include <cassert>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "povrayfc/geometry.h"

namespace povrayfc {

// Voxel (ix, iy, iz) is the closed cell [lo + i*w, lo + (i+1)*w] on each axis, with
// w = extent / n. Neighbouring cells share their faces, so a point on a face belongs to
// both: every query here answers in terms of closed cells and errs on the inclusive side.
//
// Floating point: each axis has a margin (Margin(axis)) a little larger than the rounding
// error of any boundary or position computed from this grid's numbers. Queries treat
// cells as enlarged by that margin, which makes them conservative (never miss a voxel)
// at the cost of occasionally including a neighbour within ~1e-7 of a cell width.
class VoxelGrid {
  public:
    // Per-axis resolution cap used by Automatic(); 1024^3 voxels is far more than a
    // frame-coherence grid needs and keeps indices and VoxelSets small.
    static constexpr int kMaxAutomaticResolution = 1024;
    // Hard cap for explicit resolutions: indices are uint32_t and a VoxelSet over the
    // grid must stay allocatable.
    static constexpr std::uint64_t kMaxVoxels = std::uint64_t(1) << 31;
    // Conservative slack in units of a cell width (see class comment).
    static constexpr double kRelativeMargin = 1e-7;

    // bounds must be finite and non-empty (lo <= hi); zero or near-zero extents are padded
    // (see PaddedBounds). Throws std::invalid_argument on bad bounds or resolutions.
    VoxelGrid(const Box &bounds, int nx, int ny, int nz);

    // Resolution proportional to the (padded) extents so voxels are roughly cubic, with
    // about targetVoxels voxels in all; each axis in [1, kMaxAutomaticResolution].
    static VoxelGrid Automatic(const Box &bounds, std::size_t targetVoxels);

    // The bounds a grid over `bounds` actually covers: axes thinner than
    // max(1e-3 * largest extent, 1e-9 * largest |coordinate|) are widened symmetrically
    // to that size (1.0 if both are zero, i.e. a single point at the origin), so flat
    // scenes (a lone disc, objects in one plane) get cells with a positive width.
    // Throws std::invalid_argument for NaN, infinite or empty bounds.
    static Box PaddedBounds(const Box &bounds);

    std::size_t VoxelCount() const { return count_; }
    int Res(int axis) const {
        assert(axis >= 0 && axis < 3);
        return n_[axis];
    }
    // The (padded) box covered by the grid.
    const Box &Bounds() const { return bounds_; }
    double CellWidth(int axis) const { return w_[axis]; }
    double Margin(int axis) const { return margin_[axis]; }
    // Position of the k-th cell boundary on an axis (k = 0 .. Res(axis)).
    double Boundary(int axis, int k) const { return lo_[axis] + k * w_[axis]; }

    std::uint32_t Index(int ix, int iy, int iz) const {
        assert(ix >= 0 && ix < n_[0] && iy >= 0 && iy < n_[1] && iz >= 0 && iz < n_[2]);
        return std::uint32_t(ix) +
               std::uint32_t(n_[0]) * (std::uint32_t(iy) + std::uint32_t(n_[1]) * std::uint32_t(iz));
    }
    // Inverse of Index(); throws std::invalid_argument for index >= VoxelCount().
    void Coords(std::uint32_t index, int &ix, int &iy, int &iz) const;
    // The closed cell of a voxel.
    Box VoxelBox(int ix, int iy, int iz) const;

    // True when b lies inside the grid bounds (touching faces counts as inside). A change
    // box that is not inside cannot be expressed as grid voxels: callers must then treat
    // everything as changed. NaN boxes are never inside; empty boxes always are.
    bool BoxInside(const Box &b) const;

    // Index range [first, last] on `axis` of the cells whose closed interval, enlarged by
    // `margin`, intersects [a, b], clipped to the grid. Returns false when none does.
    bool CellRange(int axis, double a, double b, double margin, int &first, int &last) const {
        assert(axis >= 0 && axis < 3);
        if (!(a <= b)) return false;
        // Cell i's enlarged interval [lo+i*w-m, lo+(i+1)*w+m] meets [a, b] iff
        // i >= (a-m-lo)/w - 1 and i <= (b+m-lo)/w. Clamp in double before converting so
        // huge or infinite inputs cannot overflow the int conversion.
        const double n = n_[axis];
        double uLo = std::ceil((a - margin - lo_[axis]) * invW_[axis]) - 1;
        double uHi = std::floor((b + margin - lo_[axis]) * invW_[axis]);
        uLo = uLo < 0 ? 0 : (uLo > n ? n : uLo);
        uHi = uHi < -1 ? -1 : (uHi > n - 1 ? n - 1 : uHi);
        if (!(uLo <= uHi)) return false;
        first = int(uLo);
        last = int(uHi);
        return true;
    }

    // Per-axis inclusive index ranges of the voxels whose closed cell intersects closed box
    // b (clipped to the grid). Returns false when none does (b empty, NaN or outside).
    bool VoxelRange(const Box &b, int first[3], int last[3]) const;

    // Calls f(uint32_t index) once for every voxel whose closed cell intersects closed box
    // b. Parts of b outside the grid are ignored (use BoxInside to detect them).
    template <class F>
    void ForEachVoxelOverlapping(const Box &b, F f) const {
        int first[3], last[3];
        if (!VoxelRange(b, first, last)) return;
        for (int iz = first[2]; iz <= last[2]; ++iz)
            for (int iy = first[1]; iy <= last[1]; ++iy)
                for (int ix = first[0]; ix <= last[0]; ++ix) f(Index(ix, iy, iz));
    }

  private:
    Box bounds_;
    int n_[3];
    std::size_t count_;
    double lo_[3], w_[3], invW_[3], margin_[3];
};

}  // namespace povrayfc

#endif
