// ParseHasher and SignatureBuilder: see povrayfc/parse_hasher.h.
#include "povrayfc/parse_hasher.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <sstream>

#include <unistd.h>

namespace povrayfc {

namespace {

constexpr std::uint64_t kNullMarker = 0x6e756c6c6e756c6cULL;
constexpr std::uint64_t kChildMarker = 0x6368696c64000000ULL;  // "child": a child's place in a shell

std::uint64_t RandomStart() {
    std::uint64_t seed = 0;
    try {
        std::random_device device;
        seed = (static_cast<std::uint64_t>(device()) << 32) ^ device();
    } catch (...) {
        // no entropy source: time and pid still differ between runs and processes
    }
    seed ^= static_cast<std::uint64_t>(
        std::chrono::high_resolution_clock::now().time_since_epoch().count());
    seed ^= static_cast<std::uint64_t>(getpid()) << 40;
    return seed;
}

}  // namespace

std::uint64_t UniqueHashValue() {
    static const std::uint64_t start = RandomStart();
    static std::atomic<std::uint64_t> counter{0};
    // A bijection of distinct inputs: never the same value twice in this process.
    return HashFinalize64(start + counter.fetch_add(1, std::memory_order_relaxed) *
                                      0x9e3779b97f4a7c15ULL);
}

unsigned FinishEffects(double crand, bool subsurface) {
    return (crand > 0 ? kEffectCrand : 0u) | (subsurface ? kEffectSubsurface : 0u);
}

unsigned MediaEffects(int method, double jitter) {
    return (method == 1 ? kEffectMediaMethod1 : 0u) | (method == 2 ? kEffectMediaMethod2 : 0u) |
           (jitter > 0 ? kEffectMediaJitter : 0u);
}

std::vector<std::string> InexactEffectNames(unsigned effects) {
    static const char *const names[] = {"crand",        "media method 1", "media method 2",
                                        "media jitter", "subsurface",     "isosurface evaluate"};
    std::vector<std::string> result;
    for (unsigned bit = 0; bit < sizeof names / sizeof names[0]; ++bit)
        if (effects & (1u << bit)) result.emplace_back(names[bit]);
    if (effects >> (sizeof names / sizeof names[0])) result.emplace_back("unknown effect");
    return result;
}

bool DebugSignaturesEnabled() {
    const char *value = std::getenv("POVRAYFC_DEBUG_SIGNATURES");
    return value != nullptr && value[0] != '\0' && std::strcmp(value, "0") != 0;
}

// ---------------------------------------------------------------------------------------
// ParseHasher

ParseHasher::ParseHasher() { BeginParse(); }

void ParseHasher::BeginParse() {
    scopes_.clear();
    scopes_.push_back(Scope{kSeed, 0, kSeed, false});
    inToken_ = false;
    slots_.clear();
}

void ParseHasher::MixFloat(double value) {
    std::uint64_t bits;
    std::memcpy(&bits, &value, sizeof bits);
    MixWord(bits);
}

void ParseHasher::MixFloats(const double *values, std::size_t count) {
    if (!enabled_) return;
    MixWord(count);
    for (std::size_t i = 0; i < count; ++i) MixFloat(values[i]);
}

void ParseHasher::MixBytes(const void *data, std::size_t size) {
    if (!enabled_) return;
    const unsigned char *bytes = static_cast<const unsigned char *>(data);
    MixWord(size);
    std::size_t i = 0;
    for (; i + 8 <= size; i += 8) {
        std::uint64_t word;
        std::memcpy(&word, bytes + i, 8);
        MixWord(word);
    }
    if (i < size) {
        std::uint64_t word = 0;
        std::memcpy(&word, bytes + i, size - i);
        MixWord(word);
    }
}

void ParseHasher::MixString(const char *text) {
    if (!enabled_) return;
    if (text == nullptr) {
        MixWord(kNullMarker);
        return;
    }
    MixBytes(text, std::strlen(text));
}

void ParseHasher::MixUcs2String(const unsigned short *text) {
    if (!enabled_) return;
    if (text == nullptr) {
        MixWord(kNullMarker);
        return;
    }
    std::size_t length = 0;
    while (text[length] != 0) ++length;
    MixBytes(text, length * sizeof(unsigned short));
}

bool ParseHasher::MixFileContent(const char *path) {
    if (!enabled_) return true;
    std::FILE *file = path != nullptr ? std::fopen(path, "rb") : nullptr;
    if (file == nullptr) {
        MixUnique();
        return false;
    }
    std::vector<unsigned char> buffer(1 << 20);
    std::uint64_t total = 0;
    bool ok = true;
    for (;;) {
        const std::size_t got = std::fread(buffer.data(), 1, buffer.size(), file);
        if (got > 0) {
            MixBytes(buffer.data(), got);
            total += got;
        }
        if (got < buffer.size()) {
            ok = !std::ferror(file);
            break;
        }
    }
    std::fclose(file);
    MixWord(total);
    if (!ok) MixUnique();
    return ok;
}

void ParseHasher::PushScope(bool trackShell) {
    if (!enabled_) return;
    scopes_.push_back(Scope{kSeed, 0, kSeed, trackShell});
}

std::uint64_t ParseHasher::PopChildScope(bool keep) {
    if (!enabled_) return 0;
    const Scope child = scopes_.back();
    if (scopes_.size() > 1) scopes_.pop_back();
    if (!keep) return 0;
    const std::uint64_t hash = Finish(child.hash);
    Scope &parent = scopes_.back();
    parent.hash = Mix(parent.hash, hash);
    if (parent.trackShell) parent.shell = Mix(parent.shell, kChildMarker);
    parent.effects |= child.effects;
    return hash;
}

std::uint64_t ParseHasher::PopScope(bool mixIntoParent, unsigned *effects) {
    if (!enabled_) {
        if (effects != nullptr) *effects = 0;
        return 0;
    }
    const Scope popped = scopes_.back();
    const std::uint64_t hash = Finish(popped.hash);
    if (effects != nullptr) *effects = popped.effects;
    if (scopes_.size() > 1) scopes_.pop_back();
    if (mixIntoParent) {
        MixWord(hash);
        NoteEffects(popped.effects);
    }
    return hash;
}

void ParseHasher::PopScopeIntoSlot(const void *slot) {
    if (!enabled_) return;
    unsigned effects = 0;
    const std::uint64_t hash = PopScope(false, &effects);
    if (slot != nullptr) SetSlotHash(slot, hash, effects);
}

bool ParseHasher::SlotHash(const void *slot, std::uint64_t &hash, unsigned *effects) const {
    auto found = slots_.find(slot);
    if (found == slots_.end()) return false;
    hash = found->second.hash;
    if (effects != nullptr) *effects = found->second.effects;
    return true;
}

void ParseHasher::MixSlot(const void *slot) {
    if (!enabled_) return;
    std::uint64_t hash;
    unsigned effects = 0;
    if (slot != nullptr && SlotHash(slot, hash, &effects)) {
        MixWord(hash);
        NoteEffects(effects);
    } else {
        MixUnique();
    }
}

void ParseHasher::ForgetSlots(void *const *first, std::size_t count) {
    if (!enabled_ || first == nullptr) return;
    for (std::size_t i = 0; i < count; ++i) slots_.erase(&first[i]);
}

void ParseHasher::CopySlots(void *const *from, void *const *to, std::size_t count) {
    if (!enabled_ || from == nullptr || to == nullptr) return;
    for (std::size_t i = 0; i < count; ++i) {
        auto found = slots_.find(&from[i]);
        if (found != slots_.end())
            slots_[&to[i]] = found->second;
        else
            slots_.erase(&to[i]);
    }
}

// ---------------------------------------------------------------------------------------
// SignatureBuilder

void SignatureBuilder::Reset() {
    signature_ = SceneSignature();
    debug_ = DebugSignaturesEnabled();
    current_ = Item();
    items_.clear();
}

void SignatureBuilder::MixInto(std::uint64_t &target, std::uint64_t hash) {
    target = HashFinalize64(target + hash * 0x9e3779b97f4a7c15ULL + 0x632be59bd9b4e019ULL);
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

void SignatureBuilder::BeginItem(const char *label, long line) {
    current_ = Item();
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

bool SignatureBuilder::MakeCapsule(const double a[3], const double b[3], double radius, Capsule &c) {
    c.a = Vec3{a[0], a[1], a[2]};
    c.b = Vec3{b[0], b[1], b[2]};
    // Grow like the boxes: POV-Ray's own numbers carry rounding.
    const double scale = std::max({std::fabs(a[0]), std::fabs(a[1]), std::fabs(a[2]), std::fabs(b[0]),
                                   std::fabs(b[1]), std::fabs(b[2]), radius});
    c.radius = radius * (1.0 + kRelativePad) + scale * kRelativePad + kAbsolutePad;
    return c.a.IsFinite() && c.b.IsFinite() && std::isfinite(c.radius);
}

void SignatureBuilder::SetItemCapsule(const double a[3], const double b[3], double radius) {
    Capsule c;
    if (!MakeCapsule(a, b, radius, c)) return;
    current_.hasCapsule = true;
    current_.capsule = c;
}

void SignatureBuilder::AddItemChild(std::uint64_t hash, const float lowerLeft[3], const float lengths[3],
                                    bool unbounded, bool isLightSource) {
    ChildSignature child;
    child.hash = hash;
    child.isLight = isLightSource;
    child.infinite = unbounded || !ObjectBox(lowerLeft, lengths, child.bounds);
    if (child.infinite) child.bounds = Box();
    current_.children.push_back(child);
}

void SignatureBuilder::SetChildCapsule(const double a[3], const double b[3], double radius) {
    if (current_.children.empty()) return;
    ChildSignature &child = current_.children.back();
    Capsule c;
    if (child.infinite || !MakeCapsule(a, b, radius, c)) return;
    child.hasCapsule = true;
    child.capsule = c;
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
                object.hasCapsule = current_.hasCapsule && !current_.infinite;
                object.capsule = current_.capsule;
                object.shell = current_.shell;
                object.children = std::move(current_.children);
                if (current_.lightGroup) {
                    // A light_group is where its other children are: its lights light
                    // nothing else, and their own boxes are unbounded.
                    object.infinite = false;
                    object.bounds = Box();
                    object.hasCapsule = false;
                    for (const ChildSignature &child : object.children) {
                        if (child.isLight) continue;
                        if (child.infinite) object.infinite = true;
                        object.bounds.Grow(child.bounds);
                    }
                    if (object.infinite) object.bounds = Box();
                }
                signature_.objects.push_back(std::move(object));
            }
            break;
    }
    if (debug_ && itemClass != ParseItemClass::kDiscard) items_.push_back(current_);
    current_ = Item();
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
                      index++, name, item.hash, item.line);
        out << buffer << (item.label.empty() ? "-" : item.label);
        if (item.itemClass == ParseItemClass::kObject && !item.isLight && item.addedLights)
            out << " lights";
        if (item.itemClass == ParseItemClass::kObject && item.hasObject && !item.isLight) {
            if (item.infinite) {
                out << " infinite";
            } else {
                std::snprintf(buffer, sizeof buffer, " bounds=%.9g,%.9g,%.9g,%.9g,%.9g,%.9g",
                              item.bounds.lo.x, item.bounds.lo.y, item.bounds.lo.z,
                              item.bounds.hi.x, item.bounds.hi.y, item.bounds.hi.z);
                out << buffer;
            }
        }
        out << '\n';
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
