// Change detection: render settings, camera, lights, global hashes, then objects as a
// multiset of signatures.
#include "povrayfc/change_detection.h"

#include <unordered_map>

namespace povrayfc {

namespace {

bool SameRenderSettings(const FrameSetup &a, const FrameSetup &b) {
    return a.width == b.width && a.height == b.height && a.left == b.left && a.top == b.top &&
           a.right == b.right && a.bottom == b.bottom && a.samplingMethod == b.samplingMethod &&
           a.blockSize == b.blockSize && a.optionsHash == b.optionsHash;
}

}  // namespace

Hull ObjectHull(const ObjectSignature &object) {
    return object.hasCapsule ? MakeHull(object.bounds, object.capsule) : MakeHull(object.bounds);
}

FrameChange CompareFrames(const FrameSetup &lastSetup, const SceneSignature &last, const FrameSetup &setup,
                          const SceneSignature &now, bool photons) {
    FrameChange change;
    change.newSequence = true;
    if (!SameRenderSettings(lastSetup, setup)) {
        change.fullReason = "render settings changed";
        return change;
    }
    if (setup.sceneCameraOverride) {
        change.fullReason = "camera set by the front end";
        return change;
    }
    if (now.camera != last.camera) {
        change.fullReason = "camera changed: new sequence";
        return change;
    }
    change.newSequence = false;
    if (now.lights != last.lights) {
        change.fullReason = "light sources changed";
        return change;
    }
    if (now.global != last.global) {
        change.fullReason = "global settings or atmosphere changed";
        return change;
    }

    // Objects are matched as a multiset of signatures: what vanished changed at its old
    // place, what appeared at its new one.
    std::unordered_map<std::uint64_t, std::vector<const ObjectSignature *>> before;
    for (const ObjectSignature &object : last.objects) before[object.hash].push_back(&object);
    std::vector<const ObjectSignature *> changed;
    for (const ObjectSignature &object : now.objects) {
        auto found = before.find(object.hash);
        if (found != before.end() && !found->second.empty()) {
            found->second.pop_back();
            continue;
        }
        changed.push_back(&object);
    }
    for (const auto &entry : before)
        for (const ObjectSignature *object : entry.second) changed.push_back(object);
    if (changed.empty()) return change;

    if (photons) {
        change.fullReason = "photons (the photon map depends on every object)";
        return change;
    }
    for (const ObjectSignature *object : changed) {
        if (object->infinite) {
            change.fullReason = "an unbounded object changed";
            change.hulls.clear();
            return change;
        }
        change.hulls.push_back(ObjectHull(*object));
    }
    return change;
}

}  // namespace povrayfc
