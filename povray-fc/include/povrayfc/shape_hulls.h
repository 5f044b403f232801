// Capsule hulls of POV-Ray shapes from their parameters: tighter than their bounding
// boxes where those are loosest (a slanted cylinder's box is mostly empty).
#ifndef POVRAYFC_SHAPE_HULLS_H
#define POVRAYFC_SHAPE_HULLS_H

#include "povrayfc/geometry.h"

namespace povrayfc {

// POV-Ray's 4x4 transform matrix (row-vector convention: p' = p * m, translation in row 3).
using Matrix4 = double[4][4];

// A cone or cylinder is the image, under its transform, of a shape inside the canonical
// unit cylinder (radius 1, z in [0, 1]); that image lies within the most m stretches the
// cross-section (its spectral norm, bounded from above) of the image of the axis.
Capsule CapsuleOfUnitCylinder(const Matrix4 &m);

// A cone as POV-Ray keeps it: the image under m of x^2 + y^2 <= z^2, z in [dist, 1]. It lies
// in two capsules (written to `out`; returns 2): the narrow half of its axis with the
// radius at the middle, the wide half with the full radius.
int CapsulesOfUnitCone(const Matrix4 &m, double dist, Capsule out[2]);

// A box from `lo` to `hi` under m (POV-Ray keeps a turned box so): a capsule through its
// centre along its longest edge, as thick as its cross-section's farthest corner.
Capsule CapsuleOfBox(const double lo[3], const double hi[3], const Matrix4 &m);

// A sphere of `radius` about `centre`; with a transform (an ellipsoid) it lies in a capsule
// along its longest axis (or, when it is nearly round, within radius times the most m
// stretches a vector of the transformed centre).
Capsule CapsuleOfSphere(const double centre[3], double radius, const Matrix4 *m);

}  // namespace povrayfc

#endif
