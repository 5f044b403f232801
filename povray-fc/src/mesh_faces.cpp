// The hulls of a changed mesh from its faces (mesh_faces.h).
#include "povrayfc/mesh_faces.h"

#include "povrayfc/parse_hasher.h"

namespace povrayfc {

void LastMeshFaces::Add(std::uint64_t meshKey, const MeshFaces &faces) {
    for (const MeshFace &face : faces) keys_.insert(CombineHashes(meshKey, face.key));
}

bool LastMeshFaces::Had(std::uint64_t meshKey, const MeshFace &face) const {
    return keys_.count(CombineHashes(meshKey, face.key)) != 0;
}

bool MeshChangeHulls(std::uint64_t meshKey, const MeshFaces &faces, const LastMeshFaces &last, std::size_t maxHulls,
                     std::vector<Hull> &out) {
    std::vector<Hull> hulls;
    for (const MeshFace &face : faces) {
        if (!last.Had(meshKey, face)) {
            hulls.push_back(MakeHull(face.box, face.triangle));
        } else {
            for (int i = 0; i < face.rimCount; ++i) hulls.push_back(MakeHull(face.rims[i], face.triangle));
        }
        if (hulls.size() > maxHulls) return false;
    }
    out.insert(out.end(), hulls.begin(), hulls.end());
    return true;
}

}  // namespace povrayfc
