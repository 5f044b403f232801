// Shadow blockers: a shadow test that an opaque surface answered holds for as long as
// something opaque still lies across its way to the light.
//
// POV-Ray's shadow test darkens a light fully when it meets a surface with OPAQUE_FLAG
// (trace.cpp, TracePointLightShadowRay): the light's share is then exactly nothing,
// whichever object it was and wherever it lay. So a stored sample whose shadow test an
// opaque unit answered stays exact when that unit moves, as long as some opaque solid of
// the new frame provably crosses the test's way: a moving ball's or a growing box's shadow
// is traced again only where it was or is now half, not where it covers the floor in both
// frames.
//
// The proof must hold for the ray POV-Ray traced, which the stored single-precision
// segment only approximates (SegmentMargin), and for the loop's own tolerances: it
// ignores surfaces within kShadowTolerance of where it starts and of the light, and may
// restart its search at a transparent surface just in front of the solid, missing its
// first surface within that tolerance. So the solid must lie wholly between the two
// tolerances, with the ray passing through it at depth, not grazing it.
#ifndef POVRAYFC_SHADOW_BLOCKERS_H
#define POVRAYFC_SHADOW_BLOCKERS_H

#include <cstdint>
#include <vector>

#include "povrayfc/geometry.h"
#include "povrayfc/segment.h"

namespace povrayfc {

// POV-Ray's SHADOW_TOLERANCE and SMALL_TOLERANCE (the patched trace.cpp asserts both are
// no larger): a shadow test ignores surfaces this close to its origin and to the light.
constexpr double kShadowTolerance = 1e-3;

// A ball every point of which is inside a solid that darkens every shadow test crossing
// it: an opaque, shadow-casting sphere, unclipped, in no CSG and in unions that are
// opaque themselves (fc-scene decides).
struct Ball {
    Vec3 centre;
    double radius = 0.0;
};

// A solid of the frame's unit `unit` (its index in SceneSignature::units): a ball, or an
// axis-aligned box (a POV-Ray box without a transformation of its own: POV-Ray intersects
// it in world space, between its two corners, like `box`).
struct Blocker {
    Ball ball;
    std::uint32_t unit = 0;
    bool isBox = false;
    Box box;

    static Blocker OfBall(const Ball &ball, std::uint32_t unit) { return Blocker{ball, unit, false, Box{}}; }
    static Blocker OfBox(const Box &box, std::uint32_t unit) { return Blocker{Ball{}, unit, true, box}; }
};

// Whether the shadow test `s` stands for (a kOpaqueBlocker segment: its origin and
// direction, and as its length the depth the test looked up to) provably meets `ball`
// within the depths the test accepts.
bool BallDarkens(const Segment &s, const Ball &ball);

// The same for an axis-aligned box: the traced ray enters and leaves it within the depths
// the test accepts, through it at depth.
bool BoxDarkens(const Segment &s, const Box &box);

// The first of `blockers` whose solid darkens it, or nullptr.
const Blocker *DarkeningBlocker(const Segment &s, const std::vector<Blocker> &blockers);

}  // namespace povrayfc

#endif
