// Boxes that only grow or move (corner_boxes.h).
// frame.h must always be the first POV-Ray file included (pulls in platform config)
#include "backend/frame.h"

#include <cstddef>

#include "backend/pattern/pattern.h"
#include "backend/scene/objects.h"
#include "backend/shape/boxes.h"

#include "corner_boxes.h"

// this must be the last file included
#include "base/povdebug.h"

namespace povrayfc
{
namespace scene
{

namespace
{

bool TextureUsesUv(const pov::TEXTURE *texture);

// A pattern (pigment, normal or texture) that maps by uv coordinates, or blends anything
// that does. A material_map picks whole textures by an image: taken as uv, to stay safe.
bool PatternUsesUv(const pov::TPATTERN *pattern)
{
    if (pattern == NULL)
        return false;
    if (pattern->Type == pov::UV_MAP_PATTERN)
        return true;
    const pov::BLEND_MAP *map = pattern->Blend_Map;
    if (map == NULL)
        return false;
    for (int i = 0; i < map->Number_Of_Entries; ++i)
    {
        const pov::BLEND_MAP_ENTRY &entry = map->Blend_Map_Entries[i];
        switch (map->Type)
        {
            case PIGMENT_TYPE:
                if (PatternUsesUv(entry.Vals.Pigment))
                    return true;
                break;
            case NORMAL_TYPE:
                if (PatternUsesUv(entry.Vals.Tnormal))
                    return true;
                break;
            case TEXTURE_TYPE:
                if (TextureUsesUv(entry.Vals.Texture))
                    return true;
                break;
            default:
                break;
        }
    }
    return false;
}

// Every layer of a texture (Next) and what each is made of.
bool TextureUsesUv(const pov::TEXTURE *texture)
{
    for (; texture != NULL; texture = static_cast<const pov::TEXTURE *>(texture->Next))
    {
        if (texture->Materials != NULL || texture->Num_Of_Mats != 0 || PatternUsesUv(texture) ||
            PatternUsesUv(texture->Pigment) || PatternUsesUv(texture->Tnormal))
            return true;
    }
    return false;
}

}  // namespace

bool CornersOf(const pov::ObjectBase *object, Box &corners)
{
    const pov::Box *box = dynamic_cast<const pov::Box *>(object);
    if (box == NULL || box->Trans != NULL || Test_Flag(box, INVERTED_FLAG))
        return false;
    corners.lo = Vec3{box->bounds[0][pov::X], box->bounds[0][pov::Y], box->bounds[0][pov::Z]};
    corners.hi = Vec3{box->bounds[1][pov::X], box->bounds[1][pov::Y], box->bounds[1][pov::Z]};
    return true;
}

bool KeepsFacesWhenResized(const pov::ObjectBase *object)
{
    return object->Clip.empty() && object->Bound.empty() && !Test_Flag(object, UV_FLAG) &&
           !TextureUsesUv(object->Texture) && !TextureUsesUv(object->Interior_Texture);
}

}  // namespace scene
}  // namespace povrayfc
