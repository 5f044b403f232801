// The static-reuse table of inexact effects.
#include "povrayfc/effect_policy.h"

#include <cstring>

namespace povrayfc {

namespace {

struct EffectRule {
    const char *name;
    bool singleThreadOnly;  // reproducible only when one thread renders in a fixed order
    bool reproducible;      // false: frames differ even when nothing changes
};

// Measured with scenes/effects/ (tests/test_effects_static.py), static 3-frame animations
// at 64x48 with fc off: radiosity, crand and jittered media rendered every frame alike
// with one thread and differently with two (per-thread random sequences, restarted each
// frame, follow which thread takes which block); media methods 1 and 2, subsurface and
// isosurface evaluate rendered alike with one and two, but are kept to one thread, which
// is all one scene each can show. Photons differed from frame to frame even with one
// thread (the photon map is shot anew from carried-on random state). A jittered area
// light rendered alike with one thread here, but some of Debian's scenes with one were
// seen to differ from frame to frame with fc off, so it is never reused.
const EffectRule kRules[] = {
    {"radiosity", true, true},          {"crand", true, true},
    {"media method 1", true, true},     {"media method 2", true, true},
    {"media jitter", true, true},       {"subsurface", true, true},
    {"isosurface evaluate", true, true}, {"jittered area light", false, false},
    {"photons", false, false},
};

}  // namespace

bool StaticFrameReproducible(const std::vector<std::string> &effects, int renderThreads) {
    for (const std::string &effect : effects) {
        const EffectRule *rule = nullptr;
        for (const EffectRule &r : kRules)
            if (effect == r.name) rule = &r;
        if (!rule || !rule->reproducible) return false;  // unknown effects: never
        if (rule->singleThreadOnly && renderThreads != 1) return false;
    }
    return true;
}

}  // namespace povrayfc
