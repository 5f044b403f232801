// Which effects fc cannot follow ray by ray still allow reusing a frame in which nothing
// changed: those whose full renders are themselves reproducible and equal from frame to
// frame (decided by tests/test_effects_static.py, one scene per effect).
#ifndef POVRAYFC_EFFECT_POLICY_H
#define POVRAYFC_EFFECT_POLICY_H

#include <string>
#include <vector>

namespace povrayfc {

// True when a frame using all of `effects` (SceneSignature::inexactEffects names), parsed
// identically to the last frame and rendered with `renderThreads` threads, renders to
// the same pixels as the last frame, so reusing them is exact.
bool StaticFrameReproducible(const std::vector<std::string> &effects, int renderThreads);

}  // namespace povrayfc

#endif
