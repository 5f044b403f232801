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

// Whether `object` is a box POV-Ray keeps between its two corners, not inverted: it has no
// transformation of its own (Box::Translate and Box::Scale move its corners until it is
// turned), so POV-Ray intersects it in world space and its normal is its face's axis. If
// so, `corners` are its corners.
bool CornersOf(const pov::ObjectBase *object, Box &corners);

// For such a box: unclipped, unbounded by `bounded_by`, and with no texture that reads the
// surface's uv coordinates (a box's depend on its corners). With the same cornerless hash
// in the next frame it shows the same colour wherever a ray still meets one of its faces
// that stayed in its plane.
bool KeepsFacesWhenResized(const pov::ObjectBase *object);

}  // namespace scene
}  // namespace povrayfc

#endif
