// Boxes that only grow or move: which boxes frame coherence may keep the rays of where a
// face stays in its plane (povray-fc/README.md, "Boxes that grow").
#ifndef POVRAYFC_SCENE_CORNER_BOXES_H
#define POVRAYFC_SCENE_CORNER_BOXES_H

#include "povrayfc/geometry.h"

namespace pov
{
class ObjectBase;
}

namespace povrayfc
{
namespace scene
{

// Whether `object` is a box POV-Ray keeps between its two corners (no transformation of its
// own, so it intersects it in world space and its normal is its face's axis), unclipped,
// unbounded by `bounded_by`, not inverted, and with no texture that reads the surface's
// uv coordinates (a box's depend on its corners); if so, `corners` are its corners. Such a
// box with the same cornerless hash in the next frame shows the same colour wherever a ray
// still meets one of its faces that stayed in its plane.
bool IsCornerBox(const pov::ObjectBase *object, Box &corners);

}  // namespace scene
}  // namespace povrayfc

#endif
