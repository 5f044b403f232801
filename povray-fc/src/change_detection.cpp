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

bool SameObjectOrder(const SceneSignature &a, const SceneSignature &b) {
    if (a.objects.size() != b.objects.size()) return false;
    for (std::size_t i = 0; i < a.objects.size(); ++i)
        if (a.objects[i].hash != b.objects[i].hash) return false;
    return true;
}

Hull ChildHull(const ChildSignature &child) {
    return child.hasCapsule ? MakeHull(child.bounds, child.capsule) : MakeHull(child.bounds);
}

// The hulls of the children that differ between two frames' versions of one CSG item (a
// multiset of child hashes). A changed light of a light_group changes every other child
// (it lights nothing else). Returns false when the change is not local to children (an
// unbounded child changed): the caller takes the whole objects.
bool AddChangedChildren(const ObjectSignature &before, const ObjectSignature &after, std::vector<Hull> &hulls) {
    std::unordered_map<std::uint64_t, std::vector<const ChildSignature *>> old;
    for (const ChildSignature &child : before.children) old[child.hash].push_back(&child);
    std::vector<const ChildSignature *> differ;
    for (const ChildSignature &child : after.children) {
        auto found = old.find(child.hash);
        if (found != old.end() && !found->second.empty()) {
            found->second.pop_back();
            continue;
        }
        differ.push_back(&child);
    }
    for (const auto &entry : old)
        for (const ChildSignature *child : entry.second) differ.push_back(child);
    bool lightChanged = false;
    for (const ChildSignature *child : differ) {
        if (child->isLight) {
            lightChanged = true;
            continue;
        }
        if (child->infinite) return false;
    }
    std::vector<Hull> found;
    if (lightChanged) {
        for (const ObjectSignature *object : {&before, &after})
            for (const ChildSignature &child : object->children) {
                if (child.isLight) continue;
                if (child.infinite) return false;
                found.push_back(ChildHull(child));
            }
    } else {
        for (const ChildSignature *child : differ) found.push_back(ChildHull(*child));
    }
    hulls.insert(hulls.end(), found.begin(), found.end());
    return true;
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

    // The objects' order decides ties between coincident surfaces: POV-Ray builds its
    // bounding tree from the objects in parse order (splitting unions in place), so the same
    // list of hashes gives the same tree.
    change.orderChanged = !SameObjectOrder(last, now);

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
    std::vector<const ObjectSignature *> vanished;
    for (const auto &entry : before)
        for (const ObjectSignature *object : entry.second) vanished.push_back(object);
    if (changed.empty() && vanished.empty()) return change;

    if (photons) {
        change.fullReason = "photons (the photon map depends on every object)";
        return change;
    }
    // A CSG item whose shell is unchanged changed only in its changed children: pair each
    // appeared CSG with a vanished one of the same shell (any pairing is conservative).
    std::vector<const ObjectSignature *> whole;
    std::vector<bool> paired(vanished.size(), false);
    for (const ObjectSignature *object : changed) {
        std::size_t match = vanished.size();
        if (!object->children.empty())
            for (std::size_t k = 0; k < vanished.size() && match == vanished.size(); ++k)
                if (!paired[k] && !vanished[k]->children.empty() && vanished[k]->shell == object->shell) match = k;
        if (match == vanished.size() || !AddChangedChildren(*vanished[match], *object, change.hulls)) {
            whole.push_back(object);
            if (match != vanished.size()) whole.push_back(vanished[match]);
        }
        if (match != vanished.size()) paired[match] = true;
    }
    for (std::size_t k = 0; k < vanished.size(); ++k)
        if (!paired[k]) whole.push_back(vanished[k]);
    for (const ObjectSignature *object : whole) {
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
