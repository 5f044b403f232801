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

// Measured (tests/test_effects_static.py renders each as a static 3-frame animation with fc
// off and compares the frames): radiosity, crand, media sampling and subsurface keep their
// random sequences per thread and restart them each frame, so one thread renders every
// frame alike; with several, which thread takes which block changes the noise. Jittered
// area lights and photons draw from generators that carry on from frame to frame.
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
