// Change detection: what differs between the last frame and this one, from their render
// settings and parse signatures.
//
// A ray's result can change only through what it ended on or what it may now meet (see
// "Units" in povray-fc/README.md). So the units of the two frames are matched by their
// hashes: a unit of the last frame with no match changed or vanished, and every sample
// with a segment that ended on it is dirty; a unit of this frame with no match is new, and
// unless a vanished unit had exactly its geometry (a change of colour, texture or interior
// alone), its hull goes to the frame's changes, which every segment is tested against.
// The old geometry needs no hull: a segment that did not end on it did not meet it.
#ifndef POVRAYFC_CHANGE_DETECTION_H
#define POVRAYFC_CHANGE_DETECTION_H

#include <cstdint>
#include <string>
#include <vector>

#include "povrayfc/frame_setup.h"
#include "povrayfc/hull.h"
#include "povrayfc/scene_signature.h"

namespace povrayfc {

struct FrameChange {
    static constexpr std::uint32_t kNew = 0xffffffffu;

    // The stored samples belong to another picture (render settings or camera changed):
    // start a new sequence. Implies a non-empty fullReason.
    bool newSequence = false;
    // Non-empty: every pixel must be traced, for this reason (lights, global settings,
    // an unbounded object's new shape...). Empty: the rest of this says what changed.
    std::string fullReason;
    // The scene's objects in parse order differ (a change, or the same objects in another
    // order): POV-Ray's bounding tree, and with it which of two surfaces tied in depth it
    // meets first, may differ (tie_watch.h).
    bool orderChanged = false;
    // Per unit of this frame: the unit of the last frame it continues (its index there):
    // unchanged, or with the same geometry (its texture or interior changed; that one is
    // also in `vanished`); kNew for a unit whose shape is new.
    std::vector<std::uint32_t> continues;
    // The last frame's units that changed or vanished (their indices there), and, for each,
    // whether the shadow tests its opaque surfaces answered still hold: a unit of this frame
    // has its shape and is opaque (its texture alone changed).
    std::vector<std::uint32_t> vanished;
    std::vector<std::uint8_t> shadowsKept;
    // Per vanished unit: a box of this frame continues it that only grew or moved
    // (UnitSignature::cornerBox): what ended on it is tested against the hulls, which hold
    // where the two boxes differ, instead of being dirty (FramePlan::kUnitFacesKept).
    std::vector<std::uint8_t> facesKept;
    // The hulls of this frame's units whose geometry is new, and the balls and boxes among
    // them that darken shadow tests (UnitSignature::ball, corners; at most kMaxBlockers).
    std::vector<Hull> hulls;
    static constexpr std::size_t kMaxBlockers = 256;
    std::vector<Blocker> blockers;
    // Those of the hulls whose unit a shadow test may pass (UnitSignature::translucent): the
    // tests opaque blockers answered are tested against them alone (README.md, "Opaque
    // blockers").
    std::vector<Hull> translucentHulls;
    // This frame's units (indices) that are unchanged parts of a merge, intersection or
    // difference another part of which changed shape (FramePlan::kUnitSiblingChanged).
    std::vector<std::uint32_t> partsBesideAChange;

    bool NothingChanged() const {
        return fullReason.empty() && hulls.empty() && vanished.empty() && !orderChanged;
    }
};

// Compares frame `now` with frame `last` (both parsed completely). `photons`: the scene
// shoots photons, whose map depends on every object, so any object change is global.
FrameChange CompareFrames(const FrameSetup &lastSetup, const SceneSignature &last, const FrameSetup &setup,
                          const SceneSignature &now, bool photons);

// The hulls a unit's signature stands for (one, or one a capsule) into `out`; returns how many.
int UnitHulls(const UnitSignature &unit, Hull out[UnitSignature::kMaxCapsules]);

}  // namespace povrayfc

#endif
