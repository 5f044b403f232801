// fc-scene: frame coherence's code that reads POV-Ray's own objects.
//
// The engine (povray-fc/) knows no POV-Ray type; what frame coherence must learn from
// POV-Ray's parsed objects is worked out here, from the hooks the patches add to the
// parser and the trace task: how an object item is cut into units (the parts a ray can
// end on, scene_signature.h), their capsules, whether they are unbounded or opaque,
// which are around the camera, a text's glyph hashes, and whether a scene has a surface
// that lets light through. Compiled against the patched POV-Ray tree, like its backend.
#ifndef POVRAYFC_SCENE_UNITS_H
#define POVRAYFC_SCENE_UNITS_H

#include <vector>

#include "povrayfc/signature_builder.h"

namespace pov
{
class ObjectBase;
class Camera;
class SceneThreadData;
}

namespace povrayfc
{
namespace scene
{

typedef pov::ObjectBase *Object;

// Cuts the object item `item` (after Post_Process) into units: through unions (and light
// groups, and a light's looks_like) to their parts, each hashed with the hashes of
// everything around it; the parts of a merge, intersection or difference are units of
// their own too (UnitSignature::cutPart) where each part's inside lies in its box, else the
// CSG is one unit hashed with all its parts. Adds each unit to `signature`, writes its index into every object below it a
// ray can report as hit (ObjectBase::fcUnit), and appends its object to `unitObjects`.
void AddUnits(Object item, SignatureBuilder &signature, std::vector<Object> &unitObjects);

// The object is unbounded: infinite, inverted (its inside is everything outside its
// surface), or a union with such a part.
bool Unbounded(Object object);

// A text's glyphs (the parts POV-Ray made, one per character of `string`): each is hashed
// by its character and its place (its translation, which kerning with the one before it
// decides), so that the glyphs a changed string keeps are unchanged.
void HashGlyphs(Object text, const unsigned short *string);

// Marks the units the camera is in (POV-Ray's inside test; with focal blur, those its
// aperture comes near): camera rays start in their medium.
void MarkUnitsAroundCamera(const pov::Camera &camera, const std::vector<Object> &unitObjects,
                           SignatureBuilder &signature, pov::SceneThreadData *thread);

// A surface of the objects (or of their parts) may let light through: not OPAQUE_FLAG.
bool LetsLightThrough(const std::vector<Object> &objects);

}  // namespace scene
}  // namespace povrayfc

#endif
