// SignatureBuilder: collects one parse's items and units into a SceneSignature.
//
// The parser hooks call it as each top-level item ends (with the item's hash from the
// ParseHasher) and, for an object item, once per unit of the object (scene_signature.h
// says what a unit is; the hook walks the object's tree and combines the hashes the
// ParseHasher gave each of its objects). Nothing here knows POV-Ray's types.
#ifndef POVRAYFC_SIGNATURE_BUILDER_H
#define POVRAYFC_SIGNATURE_BUILDER_H

#include <cstdint>
#include <string>
#include <vector>

#include "povrayfc/geometry.h"
#include "povrayfc/parse_hasher.h"
#include "povrayfc/scene_signature.h"

namespace povrayfc {

// What a finished top-level item was, as the parser hook classifies it.
enum class ParseItemClass {
    kDiscard,  // not part of the scene's content (a directive written without '#', end of file)
    kCamera,
    kGlobal,   // global_settings, fog, rainbow, sky_sphere, background, media, default...
    kObject,   // anything Parse_Object returned: objects, light sources, CSG with lights
};

class SignatureBuilder {
public:
    // The unit index of an object no unit was found for (scene_signature.h).
    static constexpr std::uint32_t kNoUnit = kUnitUnknown;

    SignatureBuilder() { Reset(); }

    // Start a new parse. Reads POVRAYFC_DEBUG_SIGNATURES from the environment.
    void Reset();

    // One top-level item: BeginItem when its first token was read (label: that token's
    // text, line: its line, both only for the debug listing), SetItemObject for an
    // object once its bounds are final, AddUnit for each of its units, EndItem with the
    // item's hash.
    void BeginItem(const char *label, long line);
    // POV-Ray's single-precision bounding box (lower left corner and lengths).
    // `unbounded`: the object's INFINITE_FLAG, or it is inverted (its inside is
    // everything outside its surface). A box that is not finite or is larger than
    // kHugeLength on some axis makes the object infinite too.
    void SetItemObject(const float lowerLeft[3], const float lengths[3], bool unbounded,
                       bool isLightSource);
    // A unit of the current item: its hash and geometry hash, its box as SetItemObject's.
    // Returns its index in the scene's units (kNoUnit when there are too many to count).
    std::uint32_t AddUnit(std::uint64_t hash, std::uint64_t geometry, const float lowerLeft[3],
                          const float lengths[3], bool unbounded);
    // After AddUnit, for a sphere, cylinder or cone: every point of the unit lies within
    // the radius of one of the `count` capsules' world-space segments [a, b]
    // (UnitSignature::kMaxCapsules at most).
    void SetUnitCapsules(std::uint32_t unit, const Capsule *capsules, int count);
    // The camera may be inside the unit (set once the camera is known, before Finish).
    void SetUnitContainsCamera(std::uint32_t unit);
    // Every object the unit is made of is opaque (UnitSignature::opaque).
    void SetUnitOpaque(std::uint32_t unit);
    // A shadow test may pass the unit (UnitSignature::translucent).
    void SetUnitTranslucent(std::uint32_t unit);
    // The unit is an opaque, shadow-casting ball (UnitSignature::ball).
    void SetUnitBall(std::uint32_t unit, const Vec3 &centre, double radius);
    // The unit is an opaque, shadow-casting box never turned (UnitSignature::corners).
    void SetUnitBlockingBox(std::uint32_t unit, const Box &box);
    // The unit is a box kept between its corners, `cornerless` everything else about it
    // (UnitSignature::cornerBox).
    void SetUnitCornerBox(std::uint32_t unit, std::uint64_t cornerless, const Box &corners);
    // The unit is a mesh cut into its faces (UnitSignature::meshFaces, meshKey,
    // meshBoxMustStay).
    void SetUnitMeshFaces(std::uint32_t unit, std::uint64_t meshKey, std::shared_ptr<const MeshFaces> faces,
                          bool boxMustStay);
    // A new merge, intersection or difference whose parts are units (its number), and the
    // unit that is one of its parts (UnitSignature::cutPart, cutGroup).
    std::uint32_t NewCutGroup() { return ++cutGroups_; }
    void SetUnitCutPart(std::uint32_t unit, std::uint32_t group);
    std::size_t UnitCount() const { return signature_.units.size(); }
    const UnitSignature &Unit(std::uint32_t unit) const { return signature_.units[unit]; }

    // addedLights: the item added light sources to the scene's global light list
    // (a light_source, or a union containing one); its hash then goes into `lights`.
    // effects: the inexact effects the item's scope collected (InexactEffect bits).
    void EndItem(ParseItemClass itemClass, std::uint64_t hash, bool addedLights,
                 unsigned effects = 0);

    // Mix a hash that is not an item into camera / lights / global (e.g. the default{}
    // block reached through a directive, or the final language version).
    void MixCamera(std::uint64_t hash) { MixInto(signature_.camera, hash); }
    void MixLights(std::uint64_t hash) { MixInto(signature_.lights, hash); }
    void MixGlobal(std::uint64_t hash) { MixInto(signature_.global, hash); }
    void MixGlobal(std::uint64_t hash, unsigned effects) {
        MixGlobal(hash);
        NoteEffects(effects);
    }

    // Effects frame coherence cannot reproduce exactly; each name is kept once, in the
    // order first seen.
    void NoteInexact(const char *name);
    void NoteEffects(unsigned effects);                  // InexactEffect bits
    void NoteMedia(int method, double jitter) { NoteEffects(MediaEffects(method, jitter)); }
    void NoteFinish(double crand, bool subsurface) { NoteEffects(FinishEffects(crand, subsurface)); }
    void NoteAreaLight(bool areaLight, bool jitter);     // area_light ... jitter
    void NoteRadiosity(bool enabled) { if (enabled) NoteInexact("radiosity"); }
    void NotePhotons(bool enabled) { if (enabled) NoteInexact("photons"); }
    void NoteSubsurface(bool enabled) { if (enabled) NoteInexact("subsurface"); }

    const SceneSignature &Signature() const { return signature_; }
    // Marks the signature complete and hands it over (the builder is Reset after).
    // With POVRAYFC_DEBUG_SIGNATURES set (and not "0"), lists every item and unit on stderr.
    SceneSignature Finish();

    // Padding and "huge" threshold for boxes.
    static constexpr double kRelativePad = 1e-4;
    static constexpr double kAbsolutePad = 1e-6;
    static constexpr double kHugeLength = 1e9;
    // The conservative world box for POV-Ray's float box; false when it is unbounded.
    static bool ObjectBox(const float lowerLeft[3], const float lengths[3], Box &box);
    // The capsule grown like the boxes (POV-Ray's own numbers carry rounding); false when
    // it cannot be used.
    static bool PaddedCapsule(const Capsule &exact, Capsule &padded);

    // The debug listing of the items and units so far (what Finish prints).
    std::string DebugListing() const;

private:
    struct Item {
        ParseItemClass itemClass = ParseItemClass::kDiscard;
        std::uint64_t hash = 0;
        std::string label;
        long line = 0;
        bool hasObject = false, infinite = false, isLight = false, addedLights = false;
        Box bounds;
        std::size_t firstUnit = 0, unitCount = 0;
    };
    static void MixInto(std::uint64_t &target, std::uint64_t hash) { target = CombineHashes(target, hash); }

    SceneSignature signature_;
    bool debug_ = false;
    Item current_;
    std::vector<Item> items_;   // only kept when debugging
    std::uint32_t cutGroups_ = 0;  // NewCutGroup's count in this parse
};

}  // namespace povrayfc

#endif
