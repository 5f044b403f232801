// ParseHasher: see povrayfc/parse_hasher.h.
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
constexpr std::uint64_t kCarriedMarker = 0x6361727269656400ULL;  // "carried": a copied object's place

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
    scopes_.push_back(Scope{kSeed, 0, kSeed, kSeed, false, 0, kSeed, 0});
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

void ParseHasher::MixCarriedWord(std::uint64_t word) {
    if (!enabled_) return;
    Scope &scope = Top();
    scope.hash = Mix(scope.hash, word);
    if (scope.trackShell) {
        scope.shell = Mix(scope.shell, kCarriedMarker);
        if (scope.appearance == 0) scope.geometry = Mix(scope.geometry, kCarriedMarker);
        if (scope.corners == 0) scope.cornerless = Mix(scope.cornerless, kCarriedMarker);
    }
}

void ParseHasher::PushScope(bool trackShell) {
    if (!enabled_) return;
    scopes_.push_back(Scope{kSeed, 0, kSeed, kSeed, trackShell, 0, kSeed, 0});
}

ParseHasher::ObjectHashes ParseHasher::PopObjectScope(ObjectRole role) {
    ObjectHashes result;
    if (!enabled_ || scopes_.size() <= 1) return result;
    const Scope popped = scopes_.back();
    scopes_.pop_back();
    result.hash = Finish(popped.hash);
    result.shell = Finish(popped.shell);
    result.geometry = Finish(popped.geometry);
    result.cornerless = Finish(popped.cornerless);
    result.effects = popped.effects;
    if (role == ObjectRole::kNone) return result;
    Scope &parent = scopes_.back();
    parent.hash = Mix(parent.hash, result.hash);
    parent.effects |= popped.effects;
    if (!parent.trackShell) return result;
    std::uint64_t shell = result.hash, geometry = result.hash, cornerless = result.hash;
    if (role == ObjectRole::kChild) {
        shell = geometry = cornerless = kChildMarker;
    } else if (role == ObjectRole::kSameObject) {
        shell = result.shell;
        geometry = result.geometry;
        cornerless = result.cornerless;
    }
    parent.shell = Mix(parent.shell, shell);
    if (parent.appearance == 0) parent.geometry = Mix(parent.geometry, geometry);
    if (parent.corners == 0) parent.cornerless = Mix(parent.cornerless, cornerless);
    return result;
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

}  // namespace povrayfc
