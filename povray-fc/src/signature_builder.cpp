// SignatureBuilder: see povrayfc/signature_builder.h.
#include "povrayfc/signature_builder.h"

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <utility>

namespace povrayfc {

void SignatureBuilder::Reset() {
    signature_ = SceneSignature();
    debug_ = DebugSignaturesEnabled();
    current_ = Item();
    items_.clear();
    cutGroups_ = 0;
}

bool SignatureBuilder::ObjectBox(const float lowerLeft[3], const float lengths[3], Box &box) {
    box = Box();
    for (int axis = 0; axis < 3; ++axis) {
        const double lo = lowerLeft[axis];
        const double length = lengths[axis];
        const double hi = lo + length;
        if (!std::isfinite(lo) || !std::isfinite(length) || !std::isfinite(hi)) return false;
        if (length < 0) return false;   // POV-Ray never makes one; do not trust it
        if (length > kHugeLength || std::fabs(lo) > kHugeLength || std::fabs(hi) > kHugeLength)
            return false;
        // Float rounding of the box and of the intersection code: pad a little.
        const double pad =
            kRelativePad * std::fmax(std::fmax(std::fabs(lo), std::fabs(hi)), length) + kAbsolutePad;
        box.lo[axis] = lo - pad;
        box.hi[axis] = hi + pad;
    }
    return true;
}

bool SignatureBuilder::PaddedCapsule(const Capsule &exact, Capsule &padded) {
    padded = exact;
    const double scale = std::max({std::fabs(exact.a.x), std::fabs(exact.a.y), std::fabs(exact.a.z),
                                   std::fabs(exact.b.x), std::fabs(exact.b.y), std::fabs(exact.b.z), exact.radius});
    padded.radius = exact.radius * (1.0 + kRelativePad) + scale * kRelativePad + kAbsolutePad;
    return padded.a.IsFinite() && padded.b.IsFinite() && std::isfinite(padded.radius);
}

void SignatureBuilder::BeginItem(const char *label, long line) {
    current_ = Item();
    current_.firstUnit = signature_.units.size();
    if (debug_) {
        current_.label = label != nullptr ? label : "";
        current_.line = line;
    }
}

void SignatureBuilder::SetItemObject(const float lowerLeft[3], const float lengths[3],
                                     bool unbounded, bool isLightSource) {
    current_.hasObject = true;
    current_.isLight = isLightSource;
    current_.infinite = unbounded || !ObjectBox(lowerLeft, lengths, current_.bounds);
    if (current_.infinite) current_.bounds = Box();
}

std::uint32_t SignatureBuilder::AddUnit(std::uint64_t hash, std::uint64_t geometry, const float lowerLeft[3],
                                        const float lengths[3], bool unbounded) {
    if (signature_.units.size() >= kUnitUnknown) return kNoUnit;
    UnitSignature unit;
    unit.hash = hash;
    unit.geometry = geometry;
    unit.infinite = unbounded || !ObjectBox(lowerLeft, lengths, unit.bounds);
    if (unit.infinite) unit.bounds = Box();
    signature_.units.push_back(unit);
    ++current_.unitCount;
    return std::uint32_t(signature_.units.size() - 1);
}

void SignatureBuilder::SetUnitCapsules(std::uint32_t unit, const Capsule *capsules, int count) {
    if (unit >= signature_.units.size() || count < 1 || count > UnitSignature::kMaxCapsules) return;
    UnitSignature &u = signature_.units[unit];
    if (u.infinite) return;
    for (int i = 0; i < count; ++i)
        if (!PaddedCapsule(capsules[i], u.capsules[i])) return;
    u.capsuleCount = count;
}

void SignatureBuilder::SetUnitContainsCamera(std::uint32_t unit) {
    if (unit < signature_.units.size()) signature_.units[unit].containsCamera = true;
}

void SignatureBuilder::SetUnitOpaque(std::uint32_t unit) {
    if (unit < signature_.units.size()) signature_.units[unit].opaque = true;
}

void SignatureBuilder::SetUnitTranslucent(std::uint32_t unit) {
    if (unit < signature_.units.size()) signature_.units[unit].translucent = true;
}

void SignatureBuilder::SetUnitCutPart(std::uint32_t unit, std::uint32_t group) {
    if (unit >= signature_.units.size()) return;
    signature_.units[unit].cutPart = true;
    signature_.units[unit].cutGroup = group;
}

void SignatureBuilder::SetUnitBall(std::uint32_t unit, const Vec3 &centre, double radius) {
    if (unit >= signature_.units.size() || !centre.IsFinite() || !(radius > 0.0) || !std::isfinite(radius)) return;
    UnitSignature &u = signature_.units[unit];
    if (u.infinite) return;
    u.hasBall = true;
    u.ball = Ball{centre, radius};
}

void SignatureBuilder::SetUnitBlockingBox(std::uint32_t unit, const Box &box) {
    if (unit >= signature_.units.size() || box.Empty() || !box.IsFinite()) return;
    UnitSignature &u = signature_.units[unit];
    if (u.infinite) return;
    u.hasBlockingBox = true;
    u.corners = box;
}

void SignatureBuilder::SetUnitCornerBox(std::uint32_t unit, std::uint64_t cornerless, const Box &corners) {
    if (unit >= signature_.units.size() || corners.Empty() || !corners.IsFinite()) return;
    UnitSignature &u = signature_.units[unit];
    if (u.infinite || u.cutPart) return;
    u.cornerBox = true;
    u.cornerless = cornerless;
    u.corners = corners;
}

void SignatureBuilder::SetUnitMeshFaces(std::uint32_t unit, std::uint64_t meshKey, std::shared_ptr<const MeshFaces> faces,
                                        bool boxMustStay) {
    if (unit >= signature_.units.size() || faces == nullptr) return;
    UnitSignature &u = signature_.units[unit];
    if (u.infinite || u.cutPart) return;
    u.meshKey = meshKey;
    u.meshFaces = std::move(faces);
    u.meshBoxMustStay = boxMustStay;
}

void SignatureBuilder::EndItem(ParseItemClass itemClass, std::uint64_t hash, bool addedLights,
                               unsigned effects) {
    if (itemClass != ParseItemClass::kDiscard) NoteEffects(effects);
    current_.itemClass = itemClass;
    current_.hash = hash;
    current_.addedLights = addedLights;
    // Whatever added to the scene's light sources changes the lighting of everything.
    if (addedLights || (itemClass == ParseItemClass::kObject && current_.isLight)) MixLights(hash);
    switch (itemClass) {
        case ParseItemClass::kDiscard:
            break;
        case ParseItemClass::kCamera:
            MixCamera(hash);
            break;
        case ParseItemClass::kGlobal:
            MixGlobal(hash);
            break;
        case ParseItemClass::kObject:
            if (!current_.hasObject) {
                // An object item without an object: nothing to place, so let any change
                // of it change the whole frame.
                MixGlobal(hash);
            } else if (!current_.isLight) {
                ObjectSignature object;
                object.hash = hash;
                object.infinite = current_.infinite;
                object.bounds = current_.bounds;
                signature_.objects.push_back(object);
            }
            break;
    }
    if (debug_ && itemClass != ParseItemClass::kDiscard) items_.push_back(current_);
    current_ = Item();
    current_.firstUnit = signature_.units.size();
}

void SignatureBuilder::NoteInexact(const char *name) {
    if (name == nullptr) return;
    for (const std::string &known : signature_.inexactEffects)
        if (known == name) return;
    signature_.inexactEffects.emplace_back(name);
}

void SignatureBuilder::NoteEffects(unsigned effects) {
    if (effects == 0) return;
    for (const std::string &name : InexactEffectNames(effects)) NoteInexact(name.c_str());
}

void SignatureBuilder::NoteAreaLight(bool areaLight, bool jitter) {
    if (areaLight && jitter) NoteInexact("jittered area light");
}

namespace {

void AppendBounds(std::ostringstream &out, bool infinite, const Box &bounds) {
    if (infinite) {
        out << " infinite";
        return;
    }
    char buffer[160];
    std::snprintf(buffer, sizeof buffer, " bounds=%.9g,%.9g,%.9g,%.9g,%.9g,%.9g", bounds.lo.x, bounds.lo.y,
                  bounds.lo.z, bounds.hi.x, bounds.hi.y, bounds.hi.z);
    out << buffer;
}

}  // namespace

std::string SignatureBuilder::DebugListing() const {
    std::ostringstream out;
    char buffer[160];
    std::size_t index = 0;
    for (const Item &item : items_) {
        const char *name = "object";
        if (item.itemClass == ParseItemClass::kCamera) name = "camera";
        if (item.itemClass == ParseItemClass::kGlobal) name = "global";
        if (item.itemClass == ParseItemClass::kObject && item.isLight) name = "light";
        std::snprintf(buffer, sizeof buffer, "povrayfc-signature: item %zu %s %016" PRIx64 " line=%ld label=",
                      index, name, item.hash, item.line);
        out << buffer << (item.label.empty() ? "-" : item.label);
        if (item.itemClass == ParseItemClass::kObject && !item.isLight && item.addedLights)
            out << " lights";
        if (item.itemClass == ParseItemClass::kObject && item.hasObject && !item.isLight)
            AppendBounds(out, item.infinite, item.bounds);
        out << '\n';
        // The item's units: `geometry` tells a change of shape from one of appearance.
        for (std::size_t u = item.firstUnit; u < item.firstUnit + item.unitCount; ++u) {
            const UnitSignature &unit = signature_.units[u];
            std::snprintf(buffer, sizeof buffer,
                          "povrayfc-signature: unit %zu item=%zu %016" PRIx64 " geometry=%016" PRIx64, u, index,
                          unit.hash, unit.geometry);
            out << buffer;
            AppendBounds(out, unit.infinite, unit.bounds);
            if (unit.containsCamera) out << " camera";
            if (unit.opaque) out << " opaque";
            if (unit.translucent) out << " translucent";
            if (unit.cutPart) out << " cut-part";
            out << '\n';
        }
        ++index;
    }
    std::snprintf(buffer, sizeof buffer,
                  "povrayfc-signature: camera %016" PRIx64 "\n"
                  "povrayfc-signature: lights %016" PRIx64 "\n"
                  "povrayfc-signature: global %016" PRIx64 "\n",
                  signature_.camera, signature_.lights, signature_.global);
    out << buffer;
    for (const std::string &effect : signature_.inexactEffects)
        out << "povrayfc-signature: inexact " << effect << '\n';
    out << "povrayfc-signature: objects " << signature_.objects.size() << '\n';
    return out.str();
}

SceneSignature SignatureBuilder::Finish() {
    signature_.complete = true;
    if (debug_) {
        const std::string listing = DebugListing();
        std::fputs(listing.c_str(), stderr);
        std::fflush(stderr);
    }
    SceneSignature done = std::move(signature_);
    Reset();
    return done;
}

}  // namespace povrayfc
