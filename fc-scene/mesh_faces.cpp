// A mesh's triangles (mesh_faces.h).
// frame.h must always be the first POV-Ray file included (pulls in platform config)
#include "backend/frame.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "backend/scene/objects.h"
#include "backend/math/matrices.h"
#include "backend/shape/mesh.h"

#include "povrayfc/parse_hasher.h"

#include "mesh_faces.h"

// this must be the last file included
#include "base/povdebug.h"

namespace povrayfc
{
namespace scene
{

namespace
{

std::uint64_t HashFloat(std::uint64_t hash, float value)
{
    std::uint32_t bits;
    std::memcpy(&bits, &value, sizeof bits);
    return CombineHashes(hash, bits);
}

Vec3 Vertex(const pov::SNGL_VECT v)
{
    return Vec3{v[pov::X], v[pov::Y], v[pov::Z]};
}

// The part of the triangle [p[0], p[1], p[2]] where coordinate `axis` is at least `floor`
// (one clip of Sutherland and Hodgman), through `toWorld`: its box, empty when none is.
template <class ToWorld>
Box BoxAbove(const Vec3 p[3], int axis, double floor, ToWorld toWorld)
{
    Box box;
    for (int i = 0; i < 3; ++i)
    {
        const Vec3 &a = p[i], &b = p[(i + 1) % 3];
        const bool aIn = a[axis] >= floor, bIn = b[axis] >= floor;
        if (aIn)
            box.Grow(toWorld(a));
        if (aIn != bIn)
        {
            const double t = (floor - a[axis]) / (b[axis] - a[axis]);
            Vec3 crossing = a + t * (b - a);
            crossing[axis] = floor;
            box.Grow(toWorld(crossing));
        }
    }
    return box;
}

// An upper bound on how much the linear part of the 4x4 matrix m stretches a vector (its
// Frobenius norm).
double Stretch(const pov::MATRIX m)
{
    double sum = 0.0;
    for (int row = 0; row < 3; ++row)
        for (int column = 0; column < 3; ++column)
            sum += m[row][column] * m[row][column];
    return std::sqrt(sum);
}

Box Widened(Box box, double by)
{
    box.lo = box.lo - Vec3{by, by, by};
    box.hi = box.hi + Vec3{by, by, by};
    return box;
}

}  // namespace

std::shared_ptr<const MeshFaces> MeshFacesOf(const pov::ObjectBase *object, std::uint64_t around, std::uint64_t &meshKey,
                                             bool &boxMustStay)
{
    const pov::Mesh *mesh = dynamic_cast<const pov::Mesh *>(object);
    if (mesh == nullptr || !mesh->Clip.empty() || !mesh->Bound.empty() || Test_Flag(mesh, INVERTED_FLAG) ||
        mesh->Data == nullptr || mesh->Data->Number_Of_Triangles > kMaxFaces)
        return nullptr;
    // A transformation intersects the ray in the mesh's space: what that rounds (about 1e-16
    // of the ray's origin, times the transformation's condition) must stay far inside the
    // segments' margin (2^-19 of it), and the mesh's tolerances below are stretched by it.
    const pov::TRANSFORM *trans = mesh->Trans;
    const double stretch = trans != nullptr ? Stretch(trans->matrix) : 1.0;
    if (trans != nullptr && !(stretch * Stretch(trans->inverse) <= 1e6))
        return nullptr;
    auto toWorld = [trans](const Vec3 &v) {
        if (trans == nullptr)
            return v;
        pov::VECTOR local = {v.x, v.y, v.z}, world;
        pov::MTransPoint(world, local, trans);
        return Vec3{world[pov::X], world[pov::Y], world[pov::Z]};
    };
    const pov::MESH_DATA &data = *mesh->Data;
    // How far from the mesh's origin its points lie (max norm): what its single-precision
    // numbers are rounded relative to.
    double reach = 0.0;
    for (long i = 0; i < data.Number_Of_Triangles; ++i)
        for (long index : {data.Triangles[i].P1, data.Triangles[i].P2, data.Triangles[i].P3})
            for (int axis = 0; axis < 3; ++axis)
                reach = std::max(reach, std::fabs(double(data.Vertices[index][axis])));
    // POV-Ray finds a hit on the plane it keeps in single precision (its normal and
    // distance, each rounded by at most 2^-24 of the magnitudes), then tests its projection
    // along the dominant axis (at least 1/sqrt(3) of the normal) against the triangle's:
    // such a hit lies within 9 * 2^-24 of `reach` of the triangle; 2^-18 is seven times
    // that. Each box of the mesh's tree holds its children's boxes with its length rounded
    // to single precision (its upper face below theirs by at most 2^-24 of twice `reach`,
    // and by 2^-24 of `reach` where its float sum is taken), so the boxes around a
    // triangle may end short of its upper faces by that much per level of the tree (about
    // ten for kMaxFaces triangles): within 2^-16 of `reach` of a triangle's upper faces,
    // whether a ray enters them may differ between the mesh's old tree and its new.
    const double thickness = 0x1p-18 * reach;
    const double rim = 0x1p-16 * reach;
    // In world space: the transformation stretches them, and rounds the vertices it moves.
    const double worldThickness = stretch * thickness;
    auto faces = std::make_shared<MeshFaces>();
    faces->reserve(std::size_t(data.Number_Of_Triangles));
    for (long i = 0; i < data.Number_Of_Triangles; ++i)
    {
        const pov::MESH_TRIANGLE &t = data.Triangles[i];
        const Vec3 p[3] = {Vertex(data.Vertices[t.P1]), Vertex(data.Vertices[t.P2]), Vertex(data.Vertices[t.P3])};
        // A sliver's normal is ill-conditioned: its plane may lie farther off than above.
        const Vec3 e1 = p[1] - p[0], e2 = p[2] - p[0];
        const Vec3 normal = Cross(e1, e2);
        if (Dot(normal, normal) < 1e-12 * Dot(e1, e1) * Dot(e2, e2))
            return nullptr;
        MeshFace face;
        std::uint64_t key = CombineHashes(0x6d657368666163ULL, t.Dominant_Axis);  // "meshfac"
        for (const pov::SNGL_VECT *v : {&data.Vertices[t.P1], &data.Vertices[t.P2], &data.Vertices[t.P3],
                                        &data.Normals[t.Normal_Ind]})
            for (int axis = 0; axis < 3; ++axis)
                key = HashFloat(key, (*v)[axis]);
        face.key = HashFloat(key, t.Distance);
        const Vec3 world[3] = {toWorld(p[0]), toWorld(p[1]), toWorld(p[2])};
        face.triangle = Triangle{world[0], world[1], world[2], worldThickness};
        for (const Vec3 &v : world)
            face.box.Grow(v);
        face.box = Widened(face.box, worldThickness);
        for (int axis = 0; axis < 3; ++axis)
        {
            // A hit within `thickness` of the triangle and `rim` of its top, in the mesh's
            // space, where its tree is.
            const double top = std::max({p[0][axis], p[1][axis], p[2][axis]});
            const Box near = BoxAbove(p, axis, top - rim - thickness, toWorld);
            if (!near.Empty())
                face.rims[face.rimCount++] = Widened(near, worldThickness);
        }
        faces->push_back(face);
    }
    std::uint64_t key = CombineHashes(around, 0x6d6573686b6579ULL);  // "meshkey"
    key = CombineHashes(key, std::uint64_t(mesh->Flags));
    // Both matrices: the ray is taken into the mesh's space by the inverse, which POV-Ray
    // composes step by step, not from the matrix.
    if (trans != nullptr)
        for (const pov::MATRIX *m : {&trans->matrix, &trans->inverse})
            for (int row = 0; row < 4; ++row)
                for (int column = 0; column < 4; ++column)
                {
                    std::uint64_t bits;
                    std::memcpy(&bits, &(*m)[row][column], sizeof bits);
                    key = CombineHashes(key, bits);
                }
    meshKey = key;
    boxMustStay = trans != nullptr;
    return faces;
}

}  // namespace scene
}  // namespace povrayfc
