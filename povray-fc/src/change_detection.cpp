// Change detection: render settings, camera, lights, global hashes, then units matched by
// hash (see change_detection.h).
#include "povrayfc/change_detection.h"

#include <algorithm>
#include <unordered_map>
#include <unordered_set>

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

// A multiset of 64-bit keys: Take removes one element with the key and says which.
class KeyedIndices {
  public:
    void Add(std::uint64_t key, std::uint32_t index) { map_[key].push_back(index); }
    bool Take(std::uint64_t key, std::uint32_t &index) {
        auto found = map_.find(key);
        if (found == map_.end() || found->second.empty()) return false;
        index = found->second.back();
        found->second.pop_back();
        return true;
    }
    template <class F>
    void ForEachLeft(F f) const {
        for (const auto &entry : map_)
            for (std::uint32_t index : entry.second) f(index);
    }

  private:
    std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> map_;
};

// Per vanished unit (`vanished`, indices into last.units): it is a part of a merge,
// intersection or difference every part of which vanished.
std::vector<std::uint8_t> WholeCsgChanged(const SceneSignature &last, const std::vector<std::uint32_t> &vanished) {
    std::unordered_map<std::uint32_t, std::uint32_t> parts, gone;
    for (const UnitSignature &u : last.units)
        if (u.cutPart) ++parts[u.cutGroup];
    for (std::uint32_t i : vanished)
        if (last.units[i].cutPart) ++gone[last.units[i].cutGroup];
    std::vector<std::uint8_t> whole(vanished.size(), 0);
    for (std::size_t k = 0; k < vanished.size(); ++k) {
        const UnitSignature &u = last.units[vanished[k]];
        whole[k] = u.cutPart && gone[u.cutGroup] == parts[u.cutGroup];
    }
    return whole;
}

// Adds the unit's hull to the frame's; false, with the frame made full, for an unbounded one.
bool AddHull(const UnitSignature &unit, FrameChange &change) {
    if (unit.infinite) {
        change.fullReason = "an unbounded object changed shape";
        change.hulls.clear();
        return false;
    }
    Hull hulls[UnitSignature::kMaxCapsules];
    const int count = UnitHulls(unit, hulls);
    for (int i = 0; i < count; ++i) {
        change.hulls.push_back(hulls[i]);
        if (unit.translucent) change.translucentHulls.push_back(hulls[i]);
    }
    return true;
}

// A mesh cut into its faces (UnitSignature::meshFaces) gives at most this many hulls;
// beyond, its box.
constexpr std::size_t kMaxMeshHulls = 4096;

// The hulls of a unit whose geometry is new: a mesh's changed faces (README.md, "Meshes"),
// else its own (AddHull). `lastFaces` is filled on first use.
bool AddReshapedHulls(const UnitSignature &unit, const SceneSignature &last, LastMeshFaces &lastFaces, bool &lastFacesFilled,
                      FrameChange &change) {
    if (unit.meshFaces == nullptr || unit.infinite) return AddHull(unit, change);
    if (!lastFacesFilled) {
        for (const UnitSignature &old : last.units)
            if (old.meshFaces != nullptr) lastFaces.Add(old.meshKey, *old.meshFaces, old.bounds);
        lastFacesFilled = true;
    }
    const std::size_t first = change.hulls.size();
    if (!MeshChangeHulls(unit.meshKey, *unit.meshFaces, unit.bounds, unit.meshBoxMustStay, lastFaces, kMaxMeshHulls,
                         change.hulls))
        return AddHull(unit, change);
    if (unit.translucent)
        change.translucentHulls.insert(change.translucentHulls.end(), change.hulls.begin() + first, change.hulls.end());
    return true;
}

// Closed boxes that together hold every point of `a` outside `b`: at most two slabs per
// axis, each cut to what is left of `a` on the axes before it. Returns how many.
int BoxMinus(const Box &a, const Box &b, Box out[6]) {
    if (!a.Overlaps(b)) {
        out[0] = a;
        return 1;
    }
    int count = 0;
    Box rest = a;
    for (int axis = 0; axis < 3; ++axis) {
        if (rest.lo[axis] < b.lo[axis]) {
            Box below = rest;
            below.hi[axis] = b.lo[axis];
            out[count++] = below;
            rest.lo[axis] = b.lo[axis];
        }
        if (rest.hi[axis] > b.hi[axis]) {
            Box above = rest;
            above.lo[axis] = b.hi[axis];
            out[count++] = above;
            rest.hi[axis] = b.hi[axis];
        }
    }
    return count;
}

// A box that only grew or moved (FrameChange::facesKept): hulls where the old box and the
// new one differ, each way. A ray that ends on neither of those places, or passes neither,
// meets the new box exactly where it met the old one (README.md, "Boxes that grow").
void AddBoxChangeHulls(const UnitSignature &old, const UnitSignature &now, FrameChange &change) {
    Box parts[12];
    int count = BoxMinus(old.corners, now.corners, parts);
    count += BoxMinus(now.corners, old.corners, parts + count);
    for (int i = 0; i < count; ++i) {
        const Hull hull = MakeHull(parts[i]);
        change.hulls.push_back(hull);
        if (old.translucent || now.translucent) change.translucentHulls.push_back(hull);
    }
}

// After the hulls: the CSGs (cutGroup, in the last frame and in this one) a part of which
// changed shape. A part recoloured in such a CSG keeps no shadow test by itself, and the
// parts that stayed in one are named (FrameChange::partsBesideAChange).
void NoteReshapedCsgs(const SceneSignature &last, const SceneSignature &now,
                      const std::vector<std::uint32_t> &unchanged,
                      const std::vector<std::pair<std::uint32_t, std::uint32_t>> &recolouredParts,
                      const std::unordered_set<std::uint32_t> &reshapedLast,
                      const std::unordered_set<std::uint32_t> &reshapedNow, FrameChange &change) {
    for (const auto &part : recolouredParts)
        if (reshapedNow.count(now.units[part.first].cutGroup) != 0 ||
            reshapedLast.count(last.units[change.vanished[part.second]].cutGroup) != 0)
            change.shadowsKept[part.second] = 0;
    for (std::uint32_t i = 0; i < now.units.size(); ++i)
        if (now.units[i].cutPart && unchanged[i] != FrameChange::kNew &&
            (reshapedNow.count(now.units[i].cutGroup) != 0 ||
             reshapedLast.count(last.units[unchanged[i]].cutGroup) != 0))
            change.partsBesideAChange.push_back(i);
}

}  // namespace

int UnitHulls(const UnitSignature &unit, Hull out[UnitSignature::kMaxCapsules]) {
    if (unit.capsuleCount == 0) {
        out[0] = MakeHull(unit.bounds);
        return 1;
    }
    // One hull a capsule, its box the unit's clipped to the capsule's: a shape's part in a
    // capsule lies in both.
    int count = 0;
    for (int i = 0; i < unit.capsuleCount; ++i) {
        const Capsule &c = unit.capsules[i];
        const Vec3 reach{c.radius, c.radius, c.radius};
        const Box box = Intersection(unit.bounds, Box{Min(c.a, c.b) - reach, Max(c.a, c.b) + reach});
        if (!box.Empty()) out[count++] = MakeHull(box, c);
    }
    if (count == 0) out[count++] = MakeHull(unit.bounds);  // rounding apart, never: stay safe
    return count;
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

    // Units are matched as a multiset of hashes.
    KeyedIndices before;
    for (std::uint32_t i = 0; i < last.units.size(); ++i) before.Add(last.units[i].hash, i);
    change.continues.assign(now.units.size(), FrameChange::kNew);
    std::vector<std::uint32_t> appeared;
    for (std::uint32_t i = 0; i < now.units.size(); ++i)
        if (!before.Take(now.units[i].hash, change.continues[i])) appeared.push_back(i);
    const std::vector<std::uint32_t> unchanged = change.continues;  // kNew where appeared
    before.ForEachLeft([&](std::uint32_t index) { change.vanished.push_back(index); });
    if (appeared.empty() && change.vanished.empty() && !change.orderChanged) return change;

    if (photons) {
        change.fullReason = "photons (the photon map depends on every object)";
        return change;
    }
    // Camera rays start in the media and refraction of whatever holds the camera: a unit
    // that does (or did) and changed reaches every camera ray.
    for (std::uint32_t i : change.vanished)
        if (last.units[i].containsCamera) change.fullReason = "an object around the camera changed";
    for (std::uint32_t i : appeared)
        if (now.units[i].containsCamera) change.fullReason = "an object around the camera changed";
    if (!change.fullReason.empty()) return change;

    // A new unit whose geometry a vanished one had changed in appearance alone: no ray that
    // did not end on the old one meets it, and an opaque one still darkens the shadow tests
    // the old one answered. Any other new unit is tested by its hull.
    //
    // A part of a merge, intersection or difference decides by its solid which surfaces of
    // the other parts count, and, where they have no texture of their own, their colour: a
    // ray need not end on it to depend on it. A part whose shape changed is tested at its
    // old place and its new, and the shadow tests the other parts stopped as opaque
    // blockers no longer hold by themselves (partsBesideAChange); one changed in appearance
    // alone is tested the same, unless every part of its CSG changed (what takes its colour
    // ended on one of them). README.md, "Parts of merges, intersections and differences".
    const std::vector<std::uint8_t> wholeCsgChanged = WholeCsgChanged(last, change.vanished);
    KeyedIndices oldShapes, oldParts;
    std::unordered_set<std::uint32_t> reshapedNow, reshapedLast;  // CSGs (cutGroup) a part of which has a hull
    change.shadowsKept.assign(change.vanished.size(), 0);
    for (std::uint32_t k = 0; k < change.vanished.size(); ++k) {
        const UnitSignature &old = last.units[change.vanished[k]];
        if (!old.cutPart) {
            oldShapes.Add(old.geometry, k);
        } else if (wholeCsgChanged[k]) {
            oldParts.Add(old.geometry, k);
        } else {
            reshapedLast.insert(old.cutGroup);
            if (!AddHull(old, change)) return change;
        }
    }
    std::vector<std::pair<std::uint32_t, std::uint32_t>> recolouredParts;  // (unit, its index in vanished)
    std::vector<std::uint8_t> taken(change.vanished.size(), 0);
    std::vector<std::uint32_t> reshaped;  // appeared units whose geometry is new
    LastMeshFaces lastFaces;
    bool lastFacesFilled = false;
    for (std::uint32_t i : appeared) {
        std::uint32_t same;
        if (now.units[i].cutPart ? oldParts.Take(now.units[i].geometry, same)
                                  : oldShapes.Take(now.units[i].geometry, same)) {
            change.shadowsKept[same] = now.units[i].opaque ? 1 : 0;
            change.continues[i] = change.vanished[same];
            taken[same] = 1;
            if (now.units[i].cutPart) recolouredParts.emplace_back(i, same);
            continue;
        }
        reshaped.push_back(i);
    }
    // Boxes that only grew or moved, matched in the scene's order among those with the same
    // key (the bars of a chart may share one): added last first, as Take gives the last.
    KeyedIndices oldBoxes;
    change.facesKept.assign(change.vanished.size(), 0);
    std::vector<std::uint32_t> byPlace(change.vanished.size());
    for (std::uint32_t k = 0; k < byPlace.size(); ++k) byPlace[k] = k;
    std::sort(byPlace.begin(), byPlace.end(),
              [&](std::uint32_t a, std::uint32_t b) { return change.vanished[a] > change.vanished[b]; });
    for (std::uint32_t k : byPlace)
        if (!taken[k] && last.units[change.vanished[k]].cornerBox)
            oldBoxes.Add(last.units[change.vanished[k]].cornerless, k);
    for (std::uint32_t i : reshaped) {
        std::uint32_t same;
        if (now.units[i].cornerBox && oldBoxes.Take(now.units[i].cornerless, same)) {
            change.facesKept[same] = 1;
            change.continues[i] = change.vanished[same];
            AddBoxChangeHulls(last.units[change.vanished[same]], now.units[i], change);
        } else {
            if (now.units[i].cutPart) reshapedNow.insert(now.units[i].cutGroup);
            if (!AddReshapedHulls(now.units[i], last, lastFaces, lastFacesFilled, change)) return change;
        }
        if (now.units[i].hasBall && change.blockers.size() < FrameChange::kMaxBlockers)
            change.blockers.push_back(Blocker::OfBall(now.units[i].ball, i));
        if (now.units[i].hasBlockingBox && change.blockers.size() < FrameChange::kMaxBlockers)
            change.blockers.push_back(Blocker::OfBox(now.units[i].corners, i));
    }
    // The parts that changed shape: where they were.
    bool bounded = true;
    oldParts.ForEachLeft([&](std::uint32_t k) {
        reshapedLast.insert(last.units[change.vanished[k]].cutGroup);
        bounded = bounded && AddHull(last.units[change.vanished[k]], change);
    });
    if (bounded) NoteReshapedCsgs(last, now, unchanged, recolouredParts, reshapedLast, reshapedNow, change);
    return change;
}

}  // namespace povrayfc
