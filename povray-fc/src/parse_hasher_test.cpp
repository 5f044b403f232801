#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <utility>
#include <limits>
#include <set>
#include <string>

#include <unistd.h>

#include "povrayfc/parse_hasher.h"

using povrayfc::ParseHasher;

namespace {

// The hash of one scope holding the given tokens.
std::uint64_t HashTokens(std::initializer_list<int> tokens) {
    ParseHasher h;
    h.PushScope();
    for (int t : tokens) h.MixToken(t);
    return h.PopScope(false);
}

}  // namespace

TEST(ParseHasher, SameInputSameHash) {
    EXPECT_EQ(HashTokens({1, 2, 3}), HashTokens({1, 2, 3}));
    ParseHasher a, b;
    for (ParseHasher *h : {&a, &b}) {
        h->MixToken(7);
        h->MixFloat(0.25);
        h->MixString("sphere");
        h->MixInt(-3);
    }
    EXPECT_EQ(a.Peek(), b.Peek());
}

// A token's digest (BeginToken ... EndToken) is a scope of its own mixed into the current
// one: the same hash, effects and shell as PushScope ... PopScope(true), inside any scope.
TEST(ParseHasher, TokenDigestEqualsAScopeOfItsOwn) {
    ParseHasher viaScope, viaToken;
    for (ParseHasher *h : {&viaScope, &viaToken}) {
        h->MixToken(1);
        h->PushScope(true);   // an item with a shell
        h->MixToken(2);
    }
    auto token = [](ParseHasher &h, bool asScope, unsigned effects, double value,
                    unsigned *effectsOut) -> std::uint64_t {
        if (asScope) h.PushScope(); else h.BeginToken();
        h.MixToken(40);
        h.MixFloat(value);
        h.NoteEffects(effects);
        return asScope ? h.PopScope(true, effectsOut) : h.EndToken(effectsOut);
    };
    unsigned e1 = 0, e2 = 0;
    EXPECT_EQ(token(viaScope, true, povrayfc::kEffectCrand, 0.5, &e1),
              token(viaToken, false, povrayfc::kEffectCrand, 0.5, &e2));
    EXPECT_EQ(e1, e2);
    EXPECT_EQ(e1, unsigned(povrayfc::kEffectCrand));
    EXPECT_EQ(token(viaScope, true, 0, 2.0, &e1), token(viaToken, false, 0, 2.0, &e2));
    EXPECT_EQ(e2, 0u);
    EXPECT_EQ(viaScope.Depth(), viaToken.Depth());
    EXPECT_EQ(viaScope.Effects(), viaToken.Effects());
    EXPECT_EQ(viaScope.Effects(), unsigned(povrayfc::kEffectCrand));
    EXPECT_EQ(viaScope.Shell(), viaToken.Shell());
    EXPECT_EQ(viaScope.Peek(), viaToken.Peek());
    EXPECT_EQ(viaScope.PopScope(false), viaToken.PopScope(false));
    EXPECT_EQ(viaScope.Peek(), viaToken.Peek());
    // A token's value reaches the scope around it.
    ParseHasher a, b;
    a.PushScope();
    b.PushScope();
    token(a, false, 0, 0.25, &e1);
    token(b, false, 0, 0.5, &e2);
    EXPECT_NE(a.PopScope(false), b.PopScope(false));
}

TEST(ParseHasher, OrderAndLengthMatter) {
    EXPECT_NE(HashTokens({1, 2, 3}), HashTokens({3, 2, 1}));
    EXPECT_NE(HashTokens({1, 2}), HashTokens({2, 1}));
    EXPECT_NE(HashTokens({1}), HashTokens({1, 1}));
    EXPECT_NE(HashTokens({0}), HashTokens({0, 0}));
    EXPECT_NE(HashTokens({}), HashTokens({0}));
}

TEST(ParseHasher, ValuesMatter) {
    ParseHasher a, b, c;
    a.MixFloat(0.5);
    b.MixFloat(0.5000000000000001);
    c.MixFloat(0.5);
    EXPECT_NE(a.Peek(), b.Peek());
    EXPECT_EQ(a.Peek(), c.Peek());

    ParseHasher s1, s2, s3;
    s1.MixString("abc");
    s2.MixString("abd");
    s3.MixString(nullptr);
    EXPECT_NE(s1.Peek(), s2.Peek());
    EXPECT_NE(s1.Peek(), s3.Peek());

    // Strings are length-delimited: "ab"+"c" is not "a"+"bc".
    ParseHasher t1, t2;
    t1.MixString("ab");
    t1.MixString("c");
    t2.MixString("a");
    t2.MixString("bc");
    EXPECT_NE(t1.Peek(), t2.Peek());

    // Bytes beyond a multiple of 8 count, and so do the bytes' values.
    const char nine[] = "123456789";
    const char nineOther[] = "123456780";
    ParseHasher b1, b2;
    b1.MixBytes(nine, 9);
    b2.MixBytes(nineOther, 9);
    EXPECT_NE(b1.Peek(), b2.Peek());

    const unsigned short u1[] = {'h', 'i', 0};
    const unsigned short u2[] = {'h', 'o', 0};
    ParseHasher w1, w2, w3;
    w1.MixUcs2String(u1);
    w2.MixUcs2String(u2);
    w3.MixUcs2String(u1);
    EXPECT_NE(w1.Peek(), w2.Peek());
    EXPECT_EQ(w1.Peek(), w3.Peek());
}

TEST(ParseHasher, ScopesAreIsolated) {
    // What happens in an isolated scope does not reach the scope around it.
    ParseHasher a, b;
    a.PushScope();
    a.MixToken(1);
    a.PushScope();
    a.MixFloat(42.0);                 // e.g. a #declare between tokens of an item
    const std::uint64_t inner = a.PopScope(false);
    a.MixToken(2);
    const std::uint64_t outerA = a.PopScope(false);

    b.PushScope();
    b.MixToken(1);
    b.PushScope();
    b.MixFloat(43.0);                 // different content, same isolation
    const std::uint64_t innerB = b.PopScope(false);
    b.MixToken(2);
    const std::uint64_t outerB = b.PopScope(false);

    EXPECT_NE(inner, innerB);
    EXPECT_EQ(outerA, outerB);
    EXPECT_EQ(outerA, HashTokens({1, 2}));
}

TEST(ParseHasher, ScopeHashDoesNotDependOnWhatCameBefore) {
    // An item is hashed the same whatever was parsed before it and at whatever depth.
    ParseHasher a;
    a.MixToken(99);
    a.MixFloat(3.0);
    a.PushScope();
    a.MixToken(5);
    const std::uint64_t first = a.PopScope(false);

    ParseHasher b;
    b.PushScope();
    b.PushScope();
    b.MixToken(5);
    const std::uint64_t second = b.PopScope(false);
    EXPECT_EQ(first, second);
}

TEST(ParseHasher, MixIntoParent) {
    ParseHasher a, b;
    a.PushScope();
    a.PushScope();
    a.MixToken(3);
    const std::uint64_t inner = a.PopScope(true);
    const std::uint64_t outer = a.PopScope(false);

    b.PushScope();
    b.MixWord(inner);
    EXPECT_EQ(outer, b.PopScope(false));
    EXPECT_NE(outer, inner);
}

TEST(ParseHasher, RootScopeIsNeverPopped) {
    ParseHasher h;
    EXPECT_EQ(h.Depth(), 1u);
    h.MixToken(1);
    const std::uint64_t root = h.PopScope(false);
    EXPECT_EQ(h.Depth(), 1u);
    EXPECT_EQ(root, h.Peek());
    h.PushScope();
    EXPECT_EQ(h.Depth(), 2u);
    h.BeginParse();
    EXPECT_EQ(h.Depth(), 1u);
}

TEST(ParseHasher, PeekMatchesPop) {
    ParseHasher h;
    h.PushScope();
    h.MixToken(11);
    const std::uint64_t peeked = h.Peek();
    EXPECT_EQ(peeked, h.PopScope(false));
}

TEST(ParseHasher, SlotHashesAreMixedWhereUsed) {
    ParseHasher h;
    void *slotA = nullptr;
    void *slotB = nullptr;
    h.SetSlotHash(&slotA, 1234);
    h.SetSlotHash(&slotB, 1234);
    std::uint64_t value = 0;
    ASSERT_TRUE(h.SlotHash(&slotA, value));
    EXPECT_EQ(value, 1234u);

    // Two identifiers with the same content hash the same where used.
    h.PushScope();
    h.MixSlot(&slotA);
    const std::uint64_t useA = h.PopScope(false);
    h.PushScope();
    h.MixSlot(&slotB);
    EXPECT_EQ(useA, h.PopScope(false));

    // Different content, different hash.
    h.SetSlotHash(&slotB, 1235);
    h.PushScope();
    h.MixSlot(&slotB);
    EXPECT_NE(useA, h.PopScope(false));
}

TEST(ParseHasher, UnknownSlotAlwaysCountsAsChanged) {
    ParseHasher h;
    void *slot = nullptr;
    std::set<std::uint64_t> seen;
    for (int i = 0; i < 100; ++i) {
        h.PushScope();
        h.MixSlot(&slot);
        seen.insert(h.PopScope(false));
    }
    EXPECT_EQ(seen.size(), 100u);
    h.PushScope();
    h.MixSlot(nullptr);
    EXPECT_EQ(seen.count(h.PopScope(false)), 0u);

    std::set<std::uint64_t> unique;
    for (int i = 0; i < 1000; ++i) unique.insert(povrayfc::UniqueHashValue());
    EXPECT_EQ(unique.size(), 1000u);
}

TEST(ParseHasher, ForgetAndCopySlots) {
    ParseHasher h;
    void *from[3] = {nullptr, nullptr, nullptr};
    void *to[3] = {nullptr, nullptr, nullptr};
    h.SetSlotHash(&from[0], 10);
    h.SetSlotHash(&from[2], 12);
    h.SetSlotHash(&to[1], 99);   // stale: from[1] has none, so to[1] must lose it
    h.CopySlots(from, to, 3);
    std::uint64_t value = 0;
    ASSERT_TRUE(h.SlotHash(&to[0], value));
    EXPECT_EQ(value, 10u);
    EXPECT_FALSE(h.SlotHash(&to[1], value));
    ASSERT_TRUE(h.SlotHash(&to[2], value));
    EXPECT_EQ(value, 12u);

    h.ForgetSlots(to, 3);
    EXPECT_FALSE(h.SlotHash(&to[0], value));
    EXPECT_FALSE(h.SlotHash(&to[2], value));
    EXPECT_TRUE(h.SlotHash(&from[0], value));
    h.ForgetSlot(&from[0]);
    EXPECT_FALSE(h.SlotHash(&from[0], value));
    EXPECT_EQ(h.SlotCount(), 1u);
    h.BeginParse();
    EXPECT_EQ(h.SlotCount(), 0u);
}

TEST(ParseHasher, FileContent) {
    char path[] = "/tmp/povrayfc-parse-hasher-XXXXXX";
    const int fd = mkstemp(path);
    ASSERT_GE(fd, 0);
    close(fd);
    auto write = [&](const std::string &content) {
        std::FILE *f = std::fopen(path, "wb");
        ASSERT_NE(f, nullptr);
        std::fwrite(content.data(), 1, content.size(), f);
        std::fclose(f);
    };
    auto hashOf = [&]() {
        ParseHasher h;
        h.PushScope();
        EXPECT_TRUE(h.MixFileContent(path));
        return h.PopScope(false);
    };
    std::string big(3 << 20, 'x');   // more than one read buffer
    write(big);
    const std::uint64_t first = hashOf();
    EXPECT_EQ(first, hashOf());
    big[(3 << 20) - 1] = 'y';        // the last byte of the last buffer counts
    write(big);
    EXPECT_NE(first, hashOf());
    write("");
    const std::uint64_t empty = hashOf();
    EXPECT_NE(empty, first);
    std::remove(path);

    // A file that cannot be read counts as changed every time.
    ParseHasher a, b;
    EXPECT_FALSE(a.MixFileContent("/nonexistent/povrayfc/file.png"));
    EXPECT_FALSE(b.MixFileContent("/nonexistent/povrayfc/file.png"));
    EXPECT_NE(a.Peek(), b.Peek());
    EXPECT_FALSE(a.MixFileContent(nullptr));
}

TEST(ParseHasher, EffectsTravelWithContent) {
    using povrayfc::kEffectCrand;
    using povrayfc::kEffectMediaJitter;
    ParseHasher h;
    void *declared = nullptr;
    void *unused = nullptr;

    // #declare F = finish { crand 0.1 }: the effect goes to F's slot, not further.
    h.PushScope();                      // a directive
    h.PushScope();                      // the right-hand side
    h.NoteEffects(povrayfc::FinishEffects(0.1, false));
    h.PopScopeIntoSlot(&declared);
    unsigned effects = 99;
    h.PopScope(false, &effects);
    EXPECT_EQ(effects, 0u);             // the directive itself has none
    EXPECT_EQ(h.Effects(), 0u);
    h.PushScope();
    h.NoteEffects(povrayfc::MediaEffects(3, 0.5));
    h.PopScopeIntoSlot(&unused);

    // An item using F has the effect; one that does not, has none.
    h.PushScope();
    h.PushScope();                      // the token's digest scope
    h.MixSlot(&declared);
    h.PopScope(true);
    h.PopScope(false, &effects);
    EXPECT_EQ(effects, unsigned(kEffectCrand));
    h.PushScope();
    h.MixToken(5);
    h.PopScope(false, &effects);
    EXPECT_EQ(effects, 0u);

    // Copies keep the effects; scopes nest.
    void *from[1] = {nullptr};
    void *to[1] = {nullptr};
    h.SetSlotHash(&from[0], 1, kEffectMediaJitter);
    h.CopySlots(from, to, 1);
    std::uint64_t hash = 0;
    ASSERT_TRUE(h.SlotHash(&to[0], hash, &effects));
    EXPECT_EQ(effects, unsigned(kEffectMediaJitter));
    h.PushScope();
    h.PushScope();
    h.MixSlot(&to[0]);
    h.MixSlot(&declared);
    h.PopScope(true);
    h.PopScope(false, &effects);
    EXPECT_EQ(effects, unsigned(kEffectMediaJitter | kEffectCrand));
}

namespace {

TEST(ParseHasherOff, KeepsNothingAndReadsNoFile) {
    povrayfc::ParseHasher h;
    h.SetEnabled(false);
    h.PushScope();
    h.MixString("sphere");
    h.MixFloat(1.5);
    h.SetSlotHash(&h, 42);
    // Invariant: a disabled hasher records no slot, hashes nothing and leaves no scope.
    EXPECT_EQ(h.SlotCount(), 0u);
    EXPECT_EQ(h.PopScope(false), 0u);
    EXPECT_EQ(h.Depth(), 1u);
    EXPECT_TRUE(h.MixFileContent("/nonexistent/file"));  // not even opened
    h.SetEnabled(true);
    h.PushScope();
    h.MixString("sphere");
    EXPECT_NE(h.PopScope(false), 0u);
}

}  // namespace

// ---------------------------------------------------------------------------------------
// Object scopes: the hash, shell and geometry of objects inside each other

namespace {

// An object scope holding one token, popped with `role` into an object scope around it;
// returns the outer scope's hashes.
ParseHasher::ObjectHashes Around(int innerToken, ParseHasher::ObjectRole role, int outerToken = 5) {
    ParseHasher h;
    h.PushObjectScope();
    h.MixToken(outerToken);
    h.PushObjectScope();
    h.MixToken(innerToken);
    h.PopObjectScope(role);
    return h.PopObjectScope(ParseHasher::ObjectRole::kOther);
}

}  // namespace

TEST(ParseHasher, AChildChangesTheParentsHashButNotItsShell) {
    using Role = ParseHasher::ObjectRole;
    const auto a = Around(1, Role::kChild), b = Around(2, Role::kChild);
    // Invariant: a union whose own tokens are unchanged keeps its shell when a child changes.
    EXPECT_NE(a.hash, b.hash);
    EXPECT_EQ(a.shell, b.shell);
    EXPECT_EQ(a.geometry, b.geometry);
    // ... but its own tokens change it.
    EXPECT_NE(a.shell, Around(1, Role::kChild, 6).shell);
}

TEST(ParseHasher, AWrappedObjectsShellIsTheWrappersAndAnythingElseCountsWhole) {
    using Role = ParseHasher::ObjectRole;
    // object { X translate ... }: X's own shell is the wrapper's.
    EXPECT_NE(Around(1, Role::kSameObject).shell, Around(2, Role::kSameObject).shell);
    // A clip, a bound or an object pattern counts whole, in the shell and the geometry.
    EXPECT_NE(Around(1, Role::kOther).shell, Around(2, Role::kOther).shell);
    EXPECT_NE(Around(1, Role::kOther).geometry, Around(2, Role::kOther).geometry);
    // No object found: the attempt leaves nothing.
    ParseHasher h, empty;
    h.PushObjectScope();
    empty.PushObjectScope();
    h.PushObjectScope();
    h.MixToken(9);
    h.PopObjectScope(Role::kNone);
    EXPECT_EQ(h.PopObjectScope(Role::kOther).hash, empty.PopObjectScope(Role::kOther).hash);
}

TEST(ParseHasher, AppearanceCountsInTheShellButNotInTheGeometry) {
    using Role = ParseHasher::ObjectRole;
    auto object = [](int colour, int size) {
        ParseHasher h;
        h.PushObjectScope();
        h.MixToken(100);
        h.MixFloat(size);
        h.BeginAppearance();
        h.MixToken(200);
        h.MixFloat(colour);
        h.EndAppearance();
        return h.PopObjectScope(Role::kOther);
    };
    // Invariant: a change of colour is a change of the object but not of its shape.
    EXPECT_NE(object(1, 1).shell, object(2, 1).shell);
    EXPECT_EQ(object(1, 1).geometry, object(2, 1).geometry);
    EXPECT_NE(object(1, 1).geometry, object(1, 2).geometry);
}

TEST(ParseHasher, CornersCountInTheShellButNotInTheCornerlessHash) {
    using Role = ParseHasher::ObjectRole;
    // box { corner, corner [scale] pigment {colour} } wrapped as object { ... flag }
    auto box = [](int corner, int colour, int flag) {
        ParseHasher h;
        h.PushObjectScope();  // the wrapper
        h.PushObjectScope();  // the box
        h.MixToken(100);
        h.BeginCorners();
        h.MixFloat(corner);
        h.EndCorners();
        h.BeginAppearance();
        h.MixFloat(colour);
        h.EndAppearance();
        const auto inner = h.PopObjectScope(Role::kSameObject);
        h.MixToken(flag);
        const auto outer = h.PopObjectScope(Role::kOther);
        return std::make_pair(inner, outer);
    };
    // Invariant: only the corners may differ between two objects whose cornerless hashes
    // agree, at every level an object { } adds.
    EXPECT_NE(box(1, 1, 7).first.shell, box(2, 1, 7).first.shell);
    EXPECT_EQ(box(1, 1, 7).first.cornerless, box(2, 1, 7).first.cornerless);
    EXPECT_EQ(box(1, 1, 7).second.cornerless, box(2, 1, 7).second.cornerless);
    EXPECT_NE(box(1, 1, 7).first.cornerless, box(1, 2, 7).first.cornerless);
    EXPECT_NE(box(1, 1, 7).second.cornerless, box(1, 1, 8).second.cornerless);
    // A child's corners are its own: the parent's cornerless hash keeps a marker for it
    // (Role::kChild), and an object parsed for another purpose (a clip, a pattern) counts
    // whole.
    auto parent = [](int corner, Role role) {
        ParseHasher h;
        h.PushObjectScope();
        h.PushObjectScope();
        h.BeginCorners();
        h.MixFloat(corner);
        h.EndCorners();
        h.PopObjectScope(role);
        return h.PopObjectScope(Role::kOther).cornerless;
    };
    EXPECT_EQ(parent(1, Role::kChild), parent(2, Role::kChild));
    EXPECT_NE(parent(1, Role::kOther), parent(2, Role::kOther));
}

TEST(ParseHasher, ACopiedObjectIdentifierIsCarriedNotMixedIntoTheShell) {
    // object { X }: X's content is in the copy's own object hashes, so the wrapper's shell
    // gets a marker; its hash still sees the content.
    auto wrapper = [](std::uint64_t content, bool carried) {
        ParseHasher h;
        h.PushObjectScope();
        h.BeginToken();
        h.MixWord(content);
        unsigned effects = 0;
        h.EndToken(&effects, carried);
        return h.PopObjectScope(ParseHasher::ObjectRole::kOther);
    };
    EXPECT_NE(wrapper(1, true).hash, wrapper(2, true).hash);
    EXPECT_EQ(wrapper(1, true).shell, wrapper(2, true).shell);
    EXPECT_EQ(wrapper(1, true).geometry, wrapper(2, true).geometry);
    EXPECT_NE(wrapper(1, false).shell, wrapper(2, false).shell);
}
