// Change detection at parse time: a 64-bit hash of what the parser consumed, per item.
//
// The patched parser (patches/0230-0245: parse hashing and signatures) feeds a ParseHasher
// with every token it reads (reserved word ids, literal values, the value of `clock`
// and of float/vector/colour/string identifiers, the content hash of every other kind
// of identifier) and with every evaluated numeric factor (so rand() and file_exists()
// are covered). Hashes live in a stack of scopes:
//  - each top-level item (object, camera, light, global_settings, fog...) is hashed in
//    its own scope, begun after its first token was read, so that the directives
//    between items are not part of any item;
//  - the right-hand side of #declare/#local, a macro argument and an array element
//    are hashed in an isolated scope; the result becomes the content hash of the
//    identifier's slot (the address of the void* that holds its value), mixed in
//    wherever the identifier is used. A slot with no known content hash mixes a value
//    never seen before, so whatever uses it counts as changed;
//  - a directive (#if, #while, #declare...) is hashed in an isolated scope too: its
//    effect on an item shows in the tokens that item then reads and in the identifiers
//    it uses, not in the directive's own tokens.
// Effects frame coherence cannot reproduce exactly (crand, media method 1 or 2...) are
// bits that travel with the hashes: a scope collects those of what it parses and of the
// identifiers it uses, so a finish declared with crand (textures.inc has one) only
// counts when an item of the scene uses it.
// Objects get hashes of their own, so that a change of one part of a model changes only
// that part (see "Units" in povray-fc/README.md): every object the parser builds is hashed
// in an object scope, which besides its hash keeps
//  - a shell: everything but its CSG children's scopes and the contents of the object
//    identifiers it copies (a copy carries the hashes of its declaration's objects), and
//  - a geometry hash: the shell without its appearance (texture, pigment, normal, finish,
//    interior, material), so that a change of colour alone is told from a change of shape;
//  - a cornerless hash: the shell without a box's corners and the moves and scalings it
//    gets before anything else (they only move its corners), so that a box that only grew
//    or moved is told from one that changed in any other way (povray-fc/README.md, "Boxes
//    that grow").
// A SignatureBuilder (signature_builder.h) sorts the finished items and units into a
// SceneSignature.
//
// Nothing here knows POV-Ray's types; the hooks translate.
#ifndef POVRAYFC_PARSE_HASHER_H
#define POVRAYFC_PARSE_HASHER_H

#include <cstddef>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

namespace povrayfc {

// splitmix64's finaliser: a bijection on 64-bit words with full avalanche.
inline std::uint64_t HashFinalize64(std::uint64_t x) {
    x ^= x >> 30;
    x *= 0xbf58476d1ce4e5b9ULL;
    x ^= x >> 27;
    x *= 0x94d049bb133111ebULL;
    x ^= x >> 31;
    return x;
}

// Two hashes into one, order mattering (b changed or moved changes the result).
inline std::uint64_t CombineHashes(std::uint64_t a, std::uint64_t b) {
    return HashFinalize64(a + b * 0x9e3779b97f4a7c15ULL + 0x632be59bd9b4e019ULL);
}

// Inexact effects the parser sees, as bits (see above).
enum InexactEffect : unsigned {
    kEffectCrand = 1u << 0,
    kEffectMediaMethod1 = 1u << 1,
    kEffectMediaMethod2 = 1u << 2,
    kEffectMediaJitter = 1u << 3,
    kEffectSubsurface = 1u << 4,
    kEffectIsosurfaceEvaluate = 1u << 5,
};
// The effects of a finish (crand > 0, subsurface {}) and of a media (method 1 or 2,
// jitter > 0).
unsigned FinishEffects(double crand, bool subsurface);
unsigned MediaEffects(int method, double jitter);
// The names SceneSignature::inexactEffects uses for the bits, in bit order.
std::vector<std::string> InexactEffectNames(unsigned effects);

// A value that no earlier call in this process returned, and that another process
// draws from an unrelated random start: mixing it makes a hash "changed".
std::uint64_t UniqueHashValue();

class ParseHasher {
public:
    ParseHasher();

    // Forget everything: only the root scope is left and no slot has a content hash.
    void BeginParse();

    // Off (Frame_Coherence off): every call below returns at once, reads no file and
    // keeps nothing, so a render without fc pays one branch per hook. On by default.
    void SetEnabled(bool enabled) {
        enabled_ = enabled;
        BeginParse();
    }
    bool Enabled() const { return enabled_; }

    // --- mixing into the current (innermost) scope; order matters ---
    void MixWord(std::uint64_t word) {
        if (!enabled_) return;
        Scope &scope = Top();
        scope.hash = Mix(scope.hash, word);
        if (scope.trackShell) {
            scope.shell = Mix(scope.shell, word);
            if (scope.appearance == 0) scope.geometry = Mix(scope.geometry, word);
            if (scope.corners == 0) scope.cornerless = Mix(scope.cornerless, word);
        }
    }
    // A word that counts in the hash but is carried elsewhere for the shell and geometry
    // (the content of an object identifier the parser copies): those get a fixed marker.
    void MixCarriedWord(std::uint64_t word);
    void MixToken(int tokenId) { MixWord(0x746f6b0000000000ULL ^ static_cast<std::uint32_t>(tokenId)); }
    void MixInt(long long value) { MixWord(static_cast<std::uint64_t>(value)); }
    // Bit pattern of the value: 0.0 and -0.0 differ, which only errs on the safe side.
    void MixFloat(double value);
    void MixFloats(const double *values, std::size_t count);
    void MixBytes(const void *data, std::size_t size);
    // A NUL-terminated string (NULL mixes a marker of its own).
    void MixString(const char *text);
    // A NUL-terminated UCS-2 string, POV-Ray's UCS2 (unsigned short).
    void MixUcs2String(const unsigned short *text);
    void MixUnique() {
        if (enabled_) MixWord(UniqueHashValue());
    }
    // Every byte of the file at `path` (an image, density or font file the parser
    // reads: its name alone would miss a file rewritten between frames). A file that
    // cannot be read mixes a unique value. Returns whether it could be read.
    bool MixFileContent(const char *path);

    // --- inexact effects of the current scope ---
    void NoteEffects(unsigned effects) {
        if (enabled_) Top().effects |= effects;
    }
    unsigned Effects() const { return Top().effects; }

    // --- scopes ---
    // trackShell: the scope also keeps a shell and a geometry hash (see above).
    void PushScope(bool trackShell = false);
    // The shell and geometry hash of the innermost scope (0 when it keeps none).
    std::uint64_t Shell() const { return Top().trackShell ? Finish(Top().shell) : 0; }
    std::uint64_t Geometry() const { return Top().trackShell ? Finish(Top().geometry) : 0; }

    // --- objects ---
    // An object's scope: PushObjectScope when the parser starts on an object, PopObjectScope
    // when it has it, saying how the object relates to the scope around it:
    enum class ObjectRole {
        kChild,       // a child of the CSG being parsed: the parent's shell gets a marker
        kSameObject,  // the object `object { ... }` wraps: it becomes the wrapper's object,
                      // so its shell and geometry are the wrapper's too
        kOther,       // anything else (a clip, a bound, an object pattern, a declaration):
                      // all of it counts in the parent's shell and geometry
        kNone,        // the parser found no object: the scope is dropped
    };
    struct ObjectHashes {
        std::uint64_t hash = 0, shell = 0, geometry = 0, cornerless = 0;
        unsigned effects = 0;
    };
    void PushObjectScope() { PushScope(true); }
    ObjectHashes PopObjectScope(ObjectRole role);
    // Tokens between BeginAppearance and EndAppearance (a texture, pigment, normal, finish,
    // interior or material of an object) do not count in its geometry hash.
    void BeginAppearance() {
        if (enabled_) ++Top().appearance;
    }
    void EndAppearance() {
        if (enabled_ && Top().appearance > 0) --Top().appearance;
    }
    // Tokens between BeginCorners and EndCorners (a box's corners, and a translate or scale
    // before the box has a texture, an interior or a transformation) do not count in its
    // cornerless hash.
    void BeginCorners() {
        if (enabled_) ++Top().corners;
    }
    void EndCorners() {
        if (enabled_ && Top().corners > 0) --Top().corners;
    }
    // Ends the innermost scope and returns its hash (and, with `effects`, its effects);
    // with mixIntoParent the hash is also mixed into the scope around it and the
    // effects go there too. The root scope is never popped: popping it returns its
    // hash and leaves it in place.
    std::uint64_t PopScope(bool mixIntoParent, unsigned *effects = nullptr);
    // Ends the innermost scope and makes it the content of `slot`.
    void PopScopeIntoSlot(const void *slot);
    // The hash the current scope would return if it were popped now.
    std::uint64_t Peek() const { return Finish(Top().hash); }
    std::size_t Depth() const { return scopes_.size(); }  // 1 = only the root

    // --- one token's digest (the patched tokenizer, for every token it reads) ---
    // BeginToken() ... EndToken(&effects) hashes what is mixed in between exactly as
    // PushScope() ... PopScope(true, &effects) would, and returns the same hash. Tokens do
    // not nest, so a scope kept beside the stack serves them and the stack is untouched: a
    // push and a pop per token were a fifth of what hashing added to Newton's parse
    // (callgrind). No scope may be pushed or popped in between.
    void BeginToken() {
        if (!enabled_) return;
        token_ = Scope{kSeed, 0, kSeed, kSeed, false, 0, kSeed, 0};
        inToken_ = true;
    }
    // carried: the token is an object identifier the parser copies (see MixCarriedWord).
    std::uint64_t EndToken(unsigned *effects, bool carried = false) {
        if (!enabled_) {
            if (effects != nullptr) *effects = 0;
            return 0;
        }
        inToken_ = false;
        const std::uint64_t hash = Finish(token_.hash);
        if (effects != nullptr) *effects = token_.effects;
        if (carried)
            MixCarriedWord(hash);
        else
            MixWord(hash);
        NoteEffects(token_.effects);
        return hash;
    }

    // --- content hashes (and effects) of identifier slots ---
    void SetSlotHash(const void *slot, std::uint64_t hash, unsigned effects = 0) {
        if (enabled_) slots_[slot] = Slot{hash, effects};
    }
    bool SlotHash(const void *slot, std::uint64_t &hash, unsigned *effects = nullptr) const;
    // Mixes the slot's content hash, or a unique value when it has none, and adds the
    // slot's effects to the current scope.
    void MixSlot(const void *slot);
    void ForgetSlot(const void *slot) {
        if (enabled_) slots_.erase(slot);
    }
    // The slots &first[0] ... &first[count-1] (an array's element pointers).
    void ForgetSlots(void *const *first, std::size_t count);
    // Gives to[i] the content hash of from[i] (or none when from[i] has none).
    void CopySlots(void *const *from, void *const *to, std::size_t count);
    std::size_t SlotCount() const { return slots_.size(); }

private:
    static std::uint64_t Finish(std::uint64_t h) { return HashFinalize64(h ^ 0x5bd1e9955bd1e995ULL); }
    // One word into a running hash: xxHash64's round (a bijection of h for any word, and of
    // the word for any h, so no single changed word goes unseen). The full avalanche is left
    // to Finish, once per scope: a parse mixes some words per token, and a finaliser per word
    // was most of what hashing added to it.
    static std::uint64_t Mix(std::uint64_t h, std::uint64_t word) {
        h += word * 0xc2b2ae3d27d4eb4fULL;
        h = (h << 31) | (h >> 33);
        return h * 0x9e3779b185ebca87ULL;
    }

    struct Scope {
        std::uint64_t hash;
        unsigned effects;
        std::uint64_t shell;
        std::uint64_t geometry;
        bool trackShell;
        int appearance;  // BeginAppearance depth
        std::uint64_t cornerless;
        int corners;     // BeginCorners depth
    };
    struct Slot {
        std::uint64_t hash;
        unsigned effects;
    };
    static constexpr std::uint64_t kSeed = 0x243f6a8885a308d3ULL;  // a fresh scope's hash (pi's fraction)
    std::vector<Scope> scopes_;
    Scope token_{kSeed, 0, kSeed, kSeed, false, 0, kSeed, 0};   // BeginToken ... EndToken
    bool inToken_ = false;                  // token_ is the innermost scope
    Scope &Top() { return inToken_ ? token_ : scopes_.back(); }
    const Scope &Top() const { return inToken_ ? token_ : scopes_.back(); }
    std::unordered_map<const void *, Slot> slots_;
    bool enabled_ = true;
};

// True when POVRAYFC_DEBUG_SIGNATURES is set to something other than "" or "0".
bool DebugSignaturesEnabled();

}  // namespace povrayfc

#endif
