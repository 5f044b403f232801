// fc-scene: units, glyphs, the camera's units and transparency, read off POV-Ray's objects
// (scene_units.h).

// frame.h must always be the first POV file included (pulls in platform config)
#include "backend/frame.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <memory>
#include <utility>
#include "backend/scene/camera.h"
#include "backend/scene/objects.h"
#include "backend/shape/boxes.h"
#include "backend/shape/cones.h"
#include "backend/shape/csg.h"
#include "backend/shape/discs.h"
#include "backend/shape/lathe.h"
#include "backend/shape/ovus.h"
#include "backend/shape/polygon.h"
#include "backend/shape/prism.h"
#include "backend/shape/sor.h"
#include "backend/shape/spheres.h"
#include "backend/shape/super.h"
#include "backend/shape/torus.h"
#include "backend/shape/triangle.h"
#include "backend/shape/truetype.h"

#include "povrayfc/parse_hasher.h"
#include "povrayfc/shape_hulls.h"

#include "corner_boxes.h"
#include "mesh_faces.h"
#include "scene_units.h"

// this must be the last file included
#include "base/povdebug.h"

namespace povrayfc
{
namespace scene
{

using pov::CompoundObject;
using pov::CSG;
using pov::CSGMerge;
using pov::CSGUnion;
using pov::LightSource;

namespace
{

// An object's own hash (or its geometry's), as the parser's object scope left it. An
// object no parse hook hashed (0: none made it) counts as changed in every frame.
std::uint64_t OwnHash(Object object, bool geometry)
{
    if (object->fcHash == 0)
        return UniqueHashValue();
    return geometry ? object->fcGeometry : object->fcHash;
}

// An object and everything below it, in order (a CSG's surfaces depend on all its parts,
// and their order decides its own ties).
std::uint64_t WholeHash(Object object, bool geometry)
{
    std::uint64_t hash = OwnHash(object, geometry);
    const CompoundObject *compound = dynamic_cast<const CompoundObject *>(object);
    if (compound != nullptr)
        for (Object child : compound->children)
            hash = CombineHashes(hash, WholeHash(child, geometry));
    return hash;
}

// Every object a ray can report as hit below `object` (Intersection::Object) is the unit.
void SetUnit(Object object, std::uint32_t unit)
{
    object->fcUnit = unit;
    const CompoundObject *compound = dynamic_cast<const CompoundObject *>(object);
    if (compound != nullptr)
        for (Object child : compound->children)
            SetUnit(child, unit);
}

// Every object a ray can report as hit below `object` is opaque to shadow tests whatever
// its texture (ComputeShadowColour looks no further than OPAQUE_FLAG).
bool AllOpaque(Object object)
{
    const CompoundObject *compound = dynamic_cast<const CompoundObject *>(object);
    if (compound == nullptr || compound->children.empty())
        return Test_Flag(object, OPAQUE_FLAG);
    for (Object child : compound->children)
        if (!AllOpaque(child))
            return false;
    return true;
}

// A tighter hull than the box for the shapes whose boxes are loosest when turned: the
// capsules their solid lies in (into `capsules`, UnitSignature::kMaxCapsules at most); how
// many, 0 for other shapes.
int CapsulesOf(Object object, Capsule capsules[])
{
    const pov::Cone *cone = dynamic_cast<const pov::Cone *>(object);
    if (cone != nullptr && cone->Trans != nullptr)
    {
        if (Test_Flag(cone, CYLINDER_FLAG))
        {
            capsules[0] = CapsuleOfUnitCylinder(cone->Trans->matrix);
            return 1;
        }
        return CapsulesOfUnitCone(cone->Trans->matrix, cone->dist, capsules);
    }
    const pov::Box *box = dynamic_cast<const pov::Box *>(object);
    if (box != nullptr && box->Trans != nullptr)
    {
        // a box without a Trans keeps its world bounds: its own box is exact
        capsules[0] = CapsuleOfBox(box->bounds[0], box->bounds[1], box->Trans->matrix);
        return 1;
    }
    const pov::Sphere *sphere = dynamic_cast<const pov::Sphere *>(object);
    if (sphere != nullptr)
    {
        // a sphere gets a Trans exactly when it becomes an ellipsoid (Sphere::Scale, Transform)
        capsules[0] = CapsuleOfSphere(sphere->Center, sphere->Radius, (sphere->Trans != nullptr) ? &sphere->Trans->matrix : nullptr);
        return 1;
    }
    return 0;
}

// Nothing about the object keeps a shadow test that meets it from going dark there: it casts
// shadows, is opaque (so is every union around it: the shadow loop asks the outermost), and
// no clipped_by or bounded_by cuts it.
bool DarkensShadows(Object object)
{
    return Test_Flag(object, OPAQUE_FLAG) && !Test_Flag(object, NO_SHADOW_FLAG) && object->Clip.empty() &&
           object->Bound.empty();
}

// A plain sphere that darkens every shadow test crossing it (shadow_blockers.h): not an
// ellipsoid (Sphere::Transform and an uneven Scale give it a Trans, and only then intersect
// it as one), not inverted.
bool BlockingBall(Object object, Ball &ball)
{
    const pov::Sphere *sphere = dynamic_cast<const pov::Sphere *>(object);
    if (sphere == nullptr || sphere->Trans != nullptr || Test_Flag(object, INVERTED_FLAG) ||
        !DarkensShadows(object))
        return false;
    ball.centre = Vec3{sphere->Center[pov::X], sphere->Center[pov::Y], sphere->Center[pov::Z]};
    ball.radius = sphere->Radius;
    return true;
}

bool IsUnion(Object object)
{
    return dynamic_cast<CSGUnion *>(object) != nullptr && dynamic_cast<CSGMerge *>(object) == nullptr;
}

// A shape whose inside test is true only within its box (for a height field it is true
// below it, for a mesh with an inside_vector wherever a ray from the point crosses it an
// odd number of times, for a plane or a quadric possibly anywhere).
bool ShapeInsideWithinBox(Object object)
{
    return dynamic_cast<pov::Sphere *>(object) != nullptr || dynamic_cast<pov::Box *>(object) != nullptr ||
           dynamic_cast<pov::Cone *>(object) != nullptr || dynamic_cast<pov::Torus *>(object) != nullptr ||
           dynamic_cast<pov::Superellipsoid *>(object) != nullptr || dynamic_cast<pov::Lathe *>(object) != nullptr ||
           dynamic_cast<pov::Prism *>(object) != nullptr || dynamic_cast<pov::Sor *>(object) != nullptr ||
           dynamic_cast<pov::Ovus *>(object) != nullptr || dynamic_cast<pov::Triangle *>(object) != nullptr ||
           dynamic_cast<pov::Disc *>(object) != nullptr || dynamic_cast<pov::Polygon *>(object) != nullptr ||
           dynamic_cast<pov::TrueType *>(object) != nullptr;
}

// Every point where the object's inside test (Inside_Object) is true lies in its box, and
// its box bounds its surfaces: made of the shapes above, with no bounded_by (the box may
// then be the bound's, which the inside test ignores) or clipped_by anywhere in it, and
// no part inverted below its top (its own inversion only swaps inside and outside of the
// shape its box bounds).
bool InsideWithinBox(Object object)
{
    if (!object->Bound.empty() || !object->Clip.empty() || Test_Flag(object, INFINITE_FLAG))
        return false;
    const CompoundObject *compound = dynamic_cast<const CompoundObject *>(object);
    if (compound == nullptr)
        return ShapeInsideWithinBox(object);
    if (dynamic_cast<const CSG *>(object) == nullptr || compound->children.empty())
        return false;
    for (Object child : compound->children)
        if (Test_Flag(child, INVERTED_FLAG) || !InsideWithinBox(child))
            return false;
    return true;
}

// A merge, intersection or difference whose parts can be units of their own: two or
// more, each one's inside within its box (README.md, "Parts of merges, intersections and
// differences"). A part that is itself a CSG stays whole.
bool CutsIntoParts(Object object)
{
    if (dynamic_cast<CSG *>(object) == nullptr || IsUnion(object))
        return false;
    const std::vector<Object> &children = static_cast<CSG *>(object)->children;
    if (children.size() < 2)
        return false;
    for (Object child : children)
        if (!InsideWithinBox(child))
            return false;
    return true;
}

// Where a change of part `i` of the CSG `object` can show: in an intersection or a
// difference a surface counts only inside every other part, so within the box of each
// other part that is not inverted (POV-Ray's own box of an intersection is made the same
// way); in a merge, anywhere in the part's own box.
void PartReach(Object object, std::size_t i, float lowerLeft[3], float lengths[3])
{
    const std::vector<Object> &children = static_cast<CSG *>(object)->children;
    float upper[3];
    for (int axis = 0; axis < 3; ++axis)
    {
        lowerLeft[axis] = children[i]->BBox.Lower_Left[axis];
        upper[axis] = lowerLeft[axis] + children[i]->BBox.Lengths[axis];
    }
    if (dynamic_cast<pov::CSGIntersection *>(object) != nullptr)
        for (std::size_t j = 0; j < children.size(); ++j)
        {
            if (j == i || Test_Flag(children[j], INVERTED_FLAG))
                continue;
            for (int axis = 0; axis < 3; ++axis)
            {
                const float low = children[j]->BBox.Lower_Left[axis];
                lowerLeft[axis] = std::max(lowerLeft[axis], low);
                upper[axis] = std::min(upper[axis], low + children[j]->BBox.Lengths[axis]);
            }
        }
    // An empty reach (the part never shows) is kept a flat box where it would be.
    for (int axis = 0; axis < 3; ++axis)
        lengths[axis] = std::max(upper[axis] - lowerLeft[axis], 0.0f);
}

// The parts of a merge, intersection or difference (CutsIntoParts), each a unit hashed
// with everything around it (`hash`: the CSG's own shell and what is around the CSG) and
// its place among the parts (the parts' order decides the CSG's own ties). A part's box
// is where a change of it can show (PartReach).
void AddParts(Object object, std::uint64_t hash, std::uint64_t geometry, SignatureBuilder &signature,
              std::vector<Object> &unitObjects)
{
    const std::vector<Object> &children = static_cast<CSG *>(object)->children;
    const std::uint32_t group = signature.NewCutGroup();
    for (std::size_t i = 0; i < children.size(); ++i)
    {
        Object part = children[i];
        const std::uint64_t place = CombineHashes(0x63757470617274ULL, i);  // "cutpart"
        float lowerLeft[3], lengths[3];
        PartReach(object, i, lowerLeft, lengths);
        const std::uint32_t unit = signature.AddUnit(CombineHashes(CombineHashes(hash, place), WholeHash(part, false)),
                                                     CombineHashes(CombineHashes(geometry, place), WholeHash(part, true)),
                                                     lowerLeft, lengths, false);
        // The solid of a sphere, cylinder or cone (inverted or not) lies in its capsules.
        Capsule capsules[UnitSignature::kMaxCapsules];
        if (dynamic_cast<CSG *>(part) == nullptr)
            signature.SetUnitCapsules(unit, capsules, CapsulesOf(part, capsules));
        // The shadow tests an opaque part stops hold while no other part changes shape
        // (FramePlan::kUnitSiblingChanged); a part is never a ball.
        if (AllOpaque(part))
            signature.SetUnitOpaque(unit);
        signature.SetUnitCutPart(unit, group);
        SetUnit(part, unit);
        if (unit != kUnitUnknown)
            unitObjects.push_back(part);
    }
}

// `darkening`: every union around the object darkens shadows (DarkensShadows).
void AddUnits(Object object, std::uint64_t path, std::uint64_t pathGeometry, bool darkening, SignatureBuilder &signature,
              std::vector<Object> &unitObjects)
{
    const std::uint64_t hash = CombineHashes(path, OwnHash(object, false));
    const std::uint64_t geometry = CombineHashes(pathGeometry, OwnHash(object, true));
    if (IsUnion(object) || dynamic_cast<LightSource *>(object) != nullptr)
    {
        // A light among a union's parts (a light_group's lights light its other parts)
        // counts for every part.
        std::uint64_t lit = hash;
        const std::vector<Object> &children = static_cast<CompoundObject *>(object)->children;
        for (Object child : children)
            if (dynamic_cast<LightSource *>(child) != nullptr)
                lit = CombineHashes(lit, WholeHash(child, false));
        const bool childrenDarken = darkening && DarkensShadows(object);
        for (Object child : children)
            AddUnits(child, lit, geometry, childrenDarken, signature, unitObjects);
        return;
    }
    if (CutsIntoParts(object))
    {
        AddParts(object, hash, geometry, signature, unitObjects);
        return;
    }
    const bool csg = dynamic_cast<CSG *>(object) != nullptr;
    const std::uint64_t unitHash = csg ? CombineHashes(path, WholeHash(object, false)) : hash;
    const std::uint64_t unitGeometry = csg ? CombineHashes(pathGeometry, WholeHash(object, true)) : geometry;
    const std::uint32_t unit = signature.AddUnit(unitHash, unitGeometry, object->BBox.Lower_Left,
                                                 object->BBox.Lengths, Unbounded(object));
    Capsule capsules[UnitSignature::kMaxCapsules];
    if (!csg)
        signature.SetUnitCapsules(unit, capsules, CapsulesOf(object, capsules));
    if (AllOpaque(object))
        signature.SetUnitOpaque(unit);
    Ball ball;
    if (darkening && BlockingBall(object, ball))
        signature.SetUnitBall(unit, ball.centre, ball.radius);
    // A box kept between its corners darkens every shadow test crossing it, as a ball does
    // (shadow_blockers.h), and may keep its faces' rays when only its corners change.
    Box corners;
    if (CornersOf(object, corners))
    {
        if (darkening && DarkensShadows(object))
            signature.SetUnitBlockingBox(unit, corners);
        if (KeepsFacesWhenResized(object))
            signature.SetUnitCornerBox(unit, CombineHashes(path, object->fcHash == 0 ? UniqueHashValue() : object->fcCornerless),
                                       corners);
    }
    std::uint64_t meshKey = 0;
    bool boxMustStay = false;
    if (std::shared_ptr<const MeshFaces> faces = MeshFacesOf(object, pathGeometry, meshKey, boxMustStay))
        signature.SetUnitMeshFaces(unit, meshKey, std::move(faces), boxMustStay);
    SetUnit(object, unit);
    if (unit != kUnitUnknown)
        unitObjects.push_back(object);
}

}  // namespace

void AddUnits(Object item, SignatureBuilder &signature, std::vector<Object> &unitObjects)
{
    const std::size_t first = unitObjects.size();
    AddUnits(item, 0, 0, true, signature, unitObjects);
    // A shadow test goes on past a surface that lets light through, from a new origin and
    // with light left. A surface whose object is opaque clears the light for good (the loop
    // may still go on, when the outermost CSG around it is not opaque: nothing after it
    // lights the point again), so only an item with such a surface can change a test an
    // opaque blocker answered further on. All its units count (more than needed: an opaque
    // part of a union with glass darkens too).
    if (!AllOpaque(item))
        for (std::size_t i = first; i < unitObjects.size(); ++i)
            signature.SetUnitTranslucent(unitObjects[i]->fcUnit);
}

bool Unbounded(Object object)
{
    if (Test_Flag(object, INFINITE_FLAG) || Test_Flag(object, INVERTED_FLAG))
        return true;
    if (dynamic_cast<CSGUnion *>(object) != nullptr)
        for (Object child : static_cast<CSG *>(object)->children)
            if (Unbounded(child))
                return true;
    return false;
}

void HashGlyphs(Object text, const unsigned short *string)
{
    std::vector<Object> &glyphs = static_cast<CSG *>(text)->children;
    bool ended = false;
    for (std::size_t i = 0; i < glyphs.size(); ++i)
    {
        ended = ended || string[i] == 0;
        std::uint64_t hash = CombineHashes(0x676c797068ULL, ended ? 0 : string[i]);
        if (glyphs[i]->Trans != nullptr)
            for (int row = 0; row < 4; ++row)
                for (int column = 0; column < 4; ++column)
                {
                    std::uint64_t bits;
                    std::memcpy(&bits, &glyphs[i]->Trans->matrix[row][column], sizeof bits);
                    hash = CombineHashes(hash, bits);
                }
        glyphs[i]->fcHash = glyphs[i]->fcGeometry = hash;
    }
}

void MarkUnitsAroundCamera(const pov::Camera &camera, const std::vector<Object> &unitObjects,
                           SignatureBuilder &signature, pov::SceneThreadData *thread)
{
    const double reach = camera.Aperture > 0.0 ? camera.Aperture : 0.0;
    const Vec3 location{camera.Location[pov::X], camera.Location[pov::Y], camera.Location[pov::Z]};
    for (std::size_t unit = 0; unit < unitObjects.size(); ++unit)
    {
        const UnitSignature &u = signature.Unit(std::uint32_t(unit));
        // The box first: the inside test of a mesh or an isosurface is no small thing.
        if (!u.infinite && !u.bounds.Near(location, reach))
            continue;
        // A part of a merge, intersection or difference decides whether the camera is in
        // the CSG wherever it is near the part's box, inside the part or not.
        if (reach > 0.0 || u.cutPart || pov::Inside_Object(camera.Location, unitObjects[unit], thread))
            signature.SetUnitContainsCamera(std::uint32_t(unit));
    }
}

bool LetsLightThrough(const std::vector<Object> &objects)
{
    for (Object object : objects)
    {
        const CompoundObject *compound = dynamic_cast<const CompoundObject *>(object);
        const bool throughParts = compound != nullptr && !compound->children.empty();
        if (throughParts ? LetsLightThrough(compound->children) : !Test_Flag(object, OPAQUE_FLAG))
            return true;
    }
    return false;
}

}  // namespace scene
}  // namespace povrayfc
