// What one frame's parse says about the scene, for change detection between frames.
//
// The parser hashes what it reads: every token and every evaluated value of a
// top-level item (so `clock`, `rand()`, macros and includes are all covered), and
// each declared identifier carries a content hash that is mixed in wherever the
// identifier is used (a texture declared once with clock and used by name).
// Objects are matched between frames as a multiset of hashes: an object whose hash
// is gone changed (its old bounds are dirty), a new hash appeared (its new bounds
// are dirty). Everything that is not a plain object (camera, lights, global
// settings, atmosphere, fog, background, sky, defaults) goes into separate hashes;
// when they change, fc renders the whole frame.
#ifndef POVRAYFC_SCENE_SIGNATURE_H
#define POVRAYFC_SCENE_SIGNATURE_H

#include <cstdint>
#include <string>
#include <vector>

#include "povrayfc/geometry.h"

namespace povrayfc {

// A direct child of a CSG item (union, merge, intersection, difference, light_group),
// hashed on its own.
struct ChildSignature {
    std::uint64_t hash = 0;
    Box bounds;              // world-space; ignored when infinite
    bool infinite = false;
    bool isLight = false;    // a light source of a light_group
    bool hasCapsule = false;
    Capsule capsule;
};

// One top-level object of the scene (after Post_Process, with its final bounds).
struct ObjectSignature {
    std::uint64_t hash = 0;
    Box bounds;              // world-space bounding box; ignored when infinite
    bool infinite = false;   // unbounded (plane, poly with no bounds...) or huge
    // A tighter hull than `bounds` for spheres, cylinders and cones: only voxels it may
    // meet are dirty when the object changes (a slanted string's box is mostly empty).
    bool hasCapsule = false;
    Capsule capsule;
    // For CSG items: the hash of everything but the children's own tokens, and the
    // children. Two frames' objects with the same shell differ only where their changed
    // children are (a CSG's surface inside a child's box depends on that child alone, or
    // on children whose boxes it overlaps).
    std::uint64_t shell = 0;
    std::vector<ChildSignature> children;
};

struct SceneSignature {
    std::uint64_t camera = 0;        // the camera: a change starts a new coherent sequence
    std::uint64_t lights = 0;        // every light source outside light groups
    std::uint64_t global = 0;        // global_settings, atmosphere/media, fog, rainbow,
                                     // sky_sphere, background, default{}, photons, radiosity
    std::vector<ObjectSignature> objects;
    // Effects fc cannot keep exact that the parser saw (e.g. "crand",
    // "isosurface evaluate", "media method 1", "media jitter", "subsurface"):
    // a frame that uses any renders in full and the log names the first.
    std::vector<std::string> inexactEffects;
    bool complete = false;           // set by the parser when the parse succeeded
};

// Hand-over from the parser (which runs before the render of the same frame, in
// another thread) to the render side. `sceneKey` identifies the parsed scene (the
// backend's SceneData pointer), so a stale signature is never used for another scene.
void PublishSceneSignature(const void *sceneKey, SceneSignature signature);
// Moves the published signature for sceneKey into `out`; false when there is none.
bool TakeSceneSignature(const void *sceneKey, SceneSignature &out);

}  // namespace povrayfc

#endif
