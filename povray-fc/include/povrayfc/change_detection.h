// Change detection: what differs between the last frame and this one, from their render
// settings and parse signatures.
#ifndef POVRAYFC_CHANGE_DETECTION_H
#define POVRAYFC_CHANGE_DETECTION_H

#include <string>
#include <vector>

#include "povrayfc/frame_setup.h"
#include "povrayfc/hull.h"
#include "povrayfc/scene_signature.h"

namespace povrayfc {

struct FrameChange {
    // The stored samples belong to another picture (render settings or camera changed):
    // start a new sequence. Implies a non-empty fullReason.
    bool newSequence = false;
    // Non-empty: every pixel must be traced, for this reason (lights, global settings,
    // an unbounded object...). Empty: only what meets `hulls` changed.
    std::string fullReason;
    std::vector<Hull> hulls;  // the old and new hulls of every changed object
    // The scene's objects in parse order differ (a change, or the same objects in another
    // order): POV-Ray's bounding tree, and with it which of two surfaces tied in depth it
    // meets first, may differ (tie_watch.h).
    bool orderChanged = false;

    bool NothingChanged() const { return fullReason.empty() && hulls.empty() && !orderChanged; }
};

// Compares frame `now` with frame `last` (both parsed completely). `photons`: the scene
// shoots photons, whose map depends on every object, so any object change is global.
FrameChange CompareFrames(const FrameSetup &lastSetup, const SceneSignature &last, const FrameSetup &setup,
                          const SceneSignature &now, bool photons);

// The hull a changed object's signature stands for.
Hull ObjectHull(const ObjectSignature &object);

}  // namespace povrayfc

#endif
