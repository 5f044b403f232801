// A mesh's triangles as frame coherence tests them when the mesh changes shape
// (povray-fc/mesh_faces.h; povray-fc/README.md, "Meshes").
#ifndef POVRAYFC_SCENE_MESH_FACES_H
#define POVRAYFC_SCENE_MESH_FACES_H

#include <cstdint>
#include <memory>

#include "povrayfc/mesh_faces.h"

namespace pov
{
class ObjectBase;
}

namespace povrayfc
{
namespace scene
{

// The faces of `object` when it is a mesh frame coherence can cut into its triangles, else
// null: no clipped_by or bounded_by, not inverted, at most kMaxFaces triangles, none of
// them a sliver, and a transformation (if any) far from singular. `meshKey` gets what else
// decides how a ray meets them: `around` (the geometry of the unions it is in), the mesh's
// flags and its transformation. `boxMustStay`: it has a transformation, so POV-Ray rounds
// its world box both ways (without one, its boxes are its triangles' own, rounded at their
// upper faces only, which the rims cover).
std::shared_ptr<const MeshFaces> MeshFacesOf(const pov::ObjectBase *object, std::uint64_t around, std::uint64_t &meshKey,
                                             bool &boxMustStay);

constexpr long kMaxFaces = 1024;

}  // namespace scene
}  // namespace povrayfc

#endif
