// What one frame's parse says about the scene, for change detection between frames.
//
// The parser hashes what it reads: every token and every evaluated value (so `clock`,
// `rand()`, macros and includes are all covered), and each declared identifier carries a
// content hash that is mixed in wherever the identifier is used (a texture declared once
// with clock and used by name). Everything that is not a plain object (camera, lights,
// global settings, atmosphere, fog, background, sky, defaults) goes into separate hashes;
// when they change, fc renders the whole frame.
//
// Objects are described twice. As top-level items in parse order (their hashes decide
// POV-Ray's bounding tree, and with it ties between coincident surfaces: tie_watch.h). And
// as units: the parts a ray can end on, each with a hash of everything it depends on (its
// own tokens and those of every CSG around it) and a hash of its geometry alone. A unit is
// a leaf object reached through unions only (a text's glyph counts as a leaf), or a whole
// merge, intersection or difference (whose surfaces depend on all of its parts). The
// parser writes each unit's index into the objects a ray can report as hit, so recorded
// rays know what they ended on (see "Units" in povray-fc/README.md).
#ifndef POVRAYFC_SCENE_SIGNATURE_H
#define POVRAYFC_SCENE_SIGNATURE_H

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "povrayfc/geometry.h"
#include "povrayfc/mesh_faces.h"
#include "povrayfc/shadow_blockers.h"

namespace povrayfc {

// What the parser writes into an object for the ray recording hooks: the index of its
// unit in SceneSignature::units, or kUnitUnknown when none was found for it (a ray that
// ends on it then depends on every change). kUnitNothing stands for "the ray hit nothing".
constexpr std::uint32_t kUnitUnknown = 0xfffffffeu;
constexpr std::uint32_t kUnitNothing = 0xffffffffu;

// One top-level object item (after Post_Process, with its final bounds).
struct ObjectSignature {
    std::uint64_t hash = 0;
    Box bounds;              // world-space bounding box; ignored when infinite
    bool infinite = false;   // unbounded (plane, poly with no bounds...) or huge
};

// One part of the scene a ray can end on (see above).
struct UnitSignature {
    std::uint64_t hash = 0;      // everything the unit's surfaces and appearance depend on
    std::uint64_t geometry = 0;  // the same without appearance (texture, interior...)
    Box bounds;                  // world-space; ignored when infinite
    bool infinite = false;       // unbounded, inverted, or huge
    // A tighter hull than `bounds` for spheres, cylinders, cones and turned boxes: every point
    // of the unit lies in one of its first capsuleCount capsules (a cone: its narrow half
    // and its wide one).
    static constexpr int kMaxCapsules = 2;
    int capsuleCount = 0;
    Capsule capsules[kMaxCapsules];
    // The camera is inside it (or, with focal blur, may be): camera rays start with it as
    // their medium, so a change of it reaches every camera ray.
    bool containsCamera = false;
    // Every surface of it is opaque to shadow tests whatever its texture (POV-Ray's
    // OPAQUE_FLAG on each object it is made of).
    bool opaque = false;
    // A shadow test may pass it with light left: its top-level item has a surface that lets
    // light through, and POV-Ray's shadow loop goes on past such a surface from a new origin
    // (README.md, "Opaque blockers").
    bool translucent = false;
    // A ball, or an axis-aligned box, inside it that darkens every shadow test crossing it
    // (shadow_blockers.h).
    bool hasBall = false;
    Ball ball;
    // A box POV-Ray keeps between its corners (fc-scene's CornersOf) has them here: a
    // blocking box (hasBlockingBox) or one that keeps its faces' rays when only its
    // corners change (cornerBox: no clip, bound or uv-mapped texture either), with the hash
    // of everything about it and around it but its corners, so that a box of the next frame
    // with the same key only grew or moved (README.md, "Boxes that grow").
    bool hasBlockingBox = false;
    bool cornerBox = false;
    std::uint64_t cornerless = 0;
    Box corners;
    // A part of a merge, intersection or difference, a unit of its own: where its solid
    // is decides which surfaces of the other parts count (POV-Ray's inside tests), so when
    // it changes in any way every ray through its old or its new box is tested, and its
    // surfaces never answer a shadow test as an opaque blocker (README.md, "Parts of
    // merges, intersections and differences").
    bool cutPart = false;
    std::uint32_t cutGroup = 0;  // for a part: which CSG of the frame it belongs to
    // A mesh cut into its triangles (null for anything else), and the key of everything
    // else that decides how a ray meets them: when its shape changes it is tested at the
    // triangles that changed instead of in its box (mesh_faces.h; README.md, "Meshes").
    std::uint64_t meshKey = 0;
    std::shared_ptr<const MeshFaces> meshFaces;
    // The mesh is transformed: POV-Ray rounds its world box both ways, so its triangles are
    // kept only while that box stays the same.
    bool meshBoxMustStay = false;
};

struct SceneSignature {
    std::uint64_t camera = 0;        // the camera: a change starts a new coherent sequence
    std::uint64_t lights = 0;        // every light source outside light groups
    std::uint64_t global = 0;        // global_settings, atmosphere/media, fog, rainbow,
                                     // sky_sphere, background, default{}, photons, radiosity
    std::vector<ObjectSignature> objects;  // top-level object items, in parse order
    std::vector<UnitSignature> units;      // by the index the parser wrote into the objects
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
