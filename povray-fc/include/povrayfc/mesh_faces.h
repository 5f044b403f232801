// Mesh faces: a mesh cut into its triangles, so that a mesh one vertex of which moves is
// tested where its triangles changed, not in its whole box (README.md, "Meshes").
#ifndef POVRAYFC_MESH_FACES_H
#define POVRAYFC_MESH_FACES_H

#include <cstddef>
#include <cstdint>
#include <memory>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "povrayfc/geometry.h"
#include "povrayfc/hull.h"

namespace povrayfc {

// One triangle of a mesh, as fc-scene reads it off POV-Ray's mesh.
struct MeshFace {
    // Everything POV-Ray's triangle test reads of it: its vertices, its plane and its
    // dominant axis, as the mesh keeps them (single precision).
    std::uint64_t key = 0;
    // In world space, thick enough to hold every point where POV-Ray's test, with the
    // plane it keeps in single precision, can find the triangle.
    Triangle triangle;
    Box box;  // the thick triangle's
    // Its rims: where the ray's entry into one of the mesh's bounding boxes around it may be
    // decided otherwise when the mesh's tree changes (the world boxes of its points within
    // a float rounding of its box's upper faces, in the mesh's space). At most three.
    int rimCount = 0;
    Box rims[3];
};
using MeshFaces = std::vector<MeshFace>;

// The faces of the last frame's meshes, each keyed with the key of its mesh
// (UnitSignature::meshKey): what POV-Ray intersects identically in this frame, if it is
// still there. And the box of the meshes with each key, where they all had the same.
class LastMeshFaces {
  public:
    void Add(std::uint64_t meshKey, const MeshFaces &faces, const Box &bounds);
    bool Had(std::uint64_t meshKey, const MeshFace &face) const;
    // The meshes of the last frame with this key had one box, `bounds`.
    bool HadBox(std::uint64_t meshKey, const Box &bounds) const;

  private:
    std::unordered_set<std::uint64_t> keys_;
    struct Boxes {
        Box bounds;
        bool several = false;  // meshes with this key had different boxes
    };
    std::unordered_map<std::uint64_t, Boxes> boxes_;
};

// The hulls of a mesh whose shape changed (`meshKey`, `faces`, its box `bounds`): each face
// none of the last frame's meshes with its key had, and the rims of the others; appended
// to `out`. False, with `out` untouched, when they would be more than `maxHulls`, or when
// a face is kept, `boxMustStay` (a transformed mesh: POV-Ray rounds its world box both
// ways) and the last frame's meshes with its key had another box.
bool MeshChangeHulls(std::uint64_t meshKey, const MeshFaces &faces, const Box &bounds, bool boxMustStay,
                     const LastMeshFaces &last, std::size_t maxHulls, std::vector<Hull> &out);

}  // namespace povrayfc

#endif
