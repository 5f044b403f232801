// The hulls of a changed mesh from its faces (mesh_faces.h).
#include "povrayfc/mesh_faces.h"

#include "povrayfc/parse_hasher.h"

namespace povrayfc {

namespace {

// Bit for bit: the boxes come from POV-Ray's single-precision ones the same way.
bool SameBox(const Box &a, const Box &b) {
    for (int axis = 0; axis < 3; ++axis)
        if (!(a.lo[axis] == b.lo[axis] && a.hi[axis] == b.hi[axis])) return false;
    return true;
}

}  // namespace

void LastMeshFaces::Add(std::uint64_t meshKey, const MeshFaces &faces, const Box &bounds) {
    for (const MeshFace &face : faces) keys_.insert(CombineHashes(meshKey, face.key));
    auto found = boxes_.find(meshKey);
    if (found == boxes_.end()) {
        boxes_[meshKey].bounds = bounds;
    } else if (!SameBox(found->second.bounds, bounds)) {
        found->second.several = true;
    }
}

bool LastMeshFaces::HadBox(std::uint64_t meshKey, const Box &bounds) const {
    auto found = boxes_.find(meshKey);
    return found != boxes_.end() && !found->second.several && SameBox(found->second.bounds, bounds);
}

bool LastMeshFaces::Had(std::uint64_t meshKey, const MeshFace &face) const {
    return keys_.count(CombineHashes(meshKey, face.key)) != 0;
}

bool MeshChangeHulls(std::uint64_t meshKey, const MeshFaces &faces, const Box &bounds, bool boxMustStay,
                     const LastMeshFaces &last, std::size_t maxHulls, std::vector<Hull> &out) {
    // A triangle kept needs the box kept too; a mesh none of whose triangles is kept (a
    // moving one, whose key changes) is all hulls, and can meet a ray nowhere else.
    const bool keeps = !boxMustStay || last.HadBox(meshKey, bounds);
    std::vector<Hull> hulls;
    for (const MeshFace &face : faces) {
        if (!last.Had(meshKey, face)) {
            hulls.push_back(MakeHull(face.box, face.triangle));
        } else {
            if (!keeps) return false;
            for (int i = 0; i < face.rimCount; ++i) hulls.push_back(MakeHull(face.rims[i], face.triangle));
        }
        if (hulls.size() > maxHulls) return false;
    }
    out.insert(out.end(), hulls.begin(), hulls.end());
    return true;
}

}  // namespace povrayfc
