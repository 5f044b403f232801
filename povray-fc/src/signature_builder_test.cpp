// Tests for SignatureBuilder: items into camera, lights, global and objects; units.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <string>

#include "povrayfc/signature_builder.h"

using povrayfc::Box;
using povrayfc::ParseItemClass;
using povrayfc::SceneSignature;
using povrayfc::SignatureBuilder;

namespace {
const float kLowerLeft[3] = {-1.0f, -2.0f, -3.0f};
const float kLengths[3] = {2.0f, 4.0f, 6.0f};
}  // namespace

TEST(SignatureBuilder, ClassifiesItems) {
    SignatureBuilder b;
    b.BeginItem("camera", 1);
    b.EndItem(ParseItemClass::kCamera, 11, false);
    b.BeginItem("global_settings", 2);
    b.EndItem(ParseItemClass::kGlobal, 22, false);
    b.BeginItem("light_source", 3);
    b.SetItemObject(kLowerLeft, kLengths, false, true);
    b.EndItem(ParseItemClass::kObject, 33, true);
    b.BeginItem("sphere", 4);
    b.SetItemObject(kLowerLeft, kLengths, false, false);
    b.EndItem(ParseItemClass::kObject, 44, false);
    b.BeginItem("declare", 5);
    b.EndItem(ParseItemClass::kDiscard, 55, false);

    const SceneSignature &s = b.Signature();
    EXPECT_NE(s.camera, 0u);
    EXPECT_NE(s.global, 0u);
    EXPECT_NE(s.lights, 0u);
    ASSERT_EQ(s.objects.size(), 1u);   // the light is not an object
    EXPECT_EQ(s.objects[0].hash, 44u);
    EXPECT_FALSE(s.objects[0].infinite);
    EXPECT_FALSE(s.complete);

    const SceneSignature done = b.Finish();
    EXPECT_TRUE(done.complete);
    EXPECT_EQ(done.objects.size(), 1u);
    // Finish resets the builder.
    EXPECT_TRUE(b.Signature().objects.empty());
    EXPECT_FALSE(b.Signature().complete);
}

TEST(SignatureBuilder, UnionWithLightIsObjectAndLight) {
    SignatureBuilder a;
    a.BeginItem("union", 1);
    a.SetItemObject(kLowerLeft, kLengths, false, false);
    a.EndItem(ParseItemClass::kObject, 7, true);
    EXPECT_EQ(a.Signature().objects.size(), 1u);
    EXPECT_NE(a.Signature().lights, 0u);

    SignatureBuilder b;   // the same union without the light
    b.BeginItem("union", 1);
    b.SetItemObject(kLowerLeft, kLengths, false, false);
    b.EndItem(ParseItemClass::kObject, 7, false);
    EXPECT_EQ(b.Signature().lights, 0u);
}

TEST(SignatureBuilder, CameraLightsGlobalAreOrderSensitive) {
    SignatureBuilder a, b, c;
    a.MixLights(1);
    a.MixLights(2);
    b.MixLights(2);
    b.MixLights(1);
    c.MixLights(1);
    c.MixLights(2);
    EXPECT_NE(a.Signature().lights, b.Signature().lights);
    EXPECT_EQ(a.Signature().lights, c.Signature().lights);
    a.MixGlobal(5);
    EXPECT_NE(a.Signature().global, b.Signature().global);
}

TEST(SignatureBuilder, ObjectWithoutBoundsGoesGlobal) {
    SignatureBuilder b;
    b.BeginItem("thing", 1);
    b.EndItem(ParseItemClass::kObject, 9, false);
    EXPECT_TRUE(b.Signature().objects.empty());
    EXPECT_NE(b.Signature().global, 0u);
}

TEST(SignatureBuilder, BoundsAreConservative) {
    Box box;
    ASSERT_TRUE(SignatureBuilder::ObjectBox(kLowerLeft, kLengths, box));
    EXPECT_LT(box.lo.x, -1.0);
    EXPECT_LT(box.lo.y, -2.0);
    EXPECT_LT(box.lo.z, -3.0);
    EXPECT_GT(box.hi.x, 1.0);
    EXPECT_GT(box.hi.y, 2.0);
    EXPECT_GT(box.hi.z, 3.0);
    // ... but only a little.
    EXPECT_GT(box.lo.x, -1.01);
    EXPECT_LT(box.hi.z, 3.01);

    // Far from the origin the pad grows with the coordinates (float rounding is relative).
    const float farLow[3] = {1e6f, 0.0f, 0.0f};
    const float unit[3] = {1.0f, 1.0f, 1.0f};
    ASSERT_TRUE(SignatureBuilder::ObjectBox(farLow, unit, box));
    EXPECT_LE(box.lo.x, 1e6 - 1e6 * 1e-5);
    EXPECT_GE(box.hi.x, 1e6 + 1.0 + 1e6 * 1e-5);

    // A degenerate (flat) box still gets a thickness.
    const float flat[3] = {1.0f, 0.0f, 1.0f};
    ASSERT_TRUE(SignatureBuilder::ObjectBox(kLowerLeft, flat, box));
    EXPECT_LT(box.lo.y, box.hi.y);
}

TEST(SignatureBuilder, HugeOrBrokenBoxesAreInfinite) {
    const float huge[3] = {2e10f, 2e10f, 2e10f};
    const float hugeLow[3] = {-1e10f, -1e10f, -1e10f};
    const float inf = std::numeric_limits<float>::infinity();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float infLength[3] = {1.0f, inf, 1.0f};
    const float nanLow[3] = {nan, 0.0f, 0.0f};
    const float negative[3] = {1.0f, -1.0f, 1.0f};
    Box box;
    EXPECT_FALSE(SignatureBuilder::ObjectBox(hugeLow, huge, box));
    EXPECT_FALSE(SignatureBuilder::ObjectBox(kLowerLeft, infLength, box));
    EXPECT_FALSE(SignatureBuilder::ObjectBox(nanLow, kLengths, box));
    EXPECT_FALSE(SignatureBuilder::ObjectBox(kLowerLeft, negative, box));

    SignatureBuilder b;
    b.BeginItem("plane", 1);
    b.SetItemObject(hugeLow, huge, false, false);
    b.EndItem(ParseItemClass::kObject, 1, false);
    b.BeginItem("sphere", 2);
    b.SetItemObject(kLowerLeft, kLengths, true, false);   // inverted / INFINITE_FLAG
    b.EndItem(ParseItemClass::kObject, 2, false);
    ASSERT_EQ(b.Signature().objects.size(), 2u);
    EXPECT_TRUE(b.Signature().objects[0].infinite);
    EXPECT_TRUE(b.Signature().objects[1].infinite);
}

TEST(SignatureBuilder, InexactEffectsOnceInOrder) {
    SignatureBuilder b;
    b.NoteMedia(3, 0.0);
    b.NoteFinish(0.0, false);
    b.NoteAreaLight(true, false);
    b.NoteAreaLight(false, true);
    b.NoteRadiosity(false);
    b.NotePhotons(false);
    b.NoteSubsurface(false);
    EXPECT_TRUE(b.Signature().inexactEffects.empty());

    b.NoteFinish(0.1, false);
    b.NoteMedia(1, 0.0);
    b.NoteMedia(2, 0.5);
    b.NoteFinish(0.3, true);
    b.NoteAreaLight(true, true);
    b.NoteInexact("isosurface evaluate");
    b.NoteRadiosity(true);
    b.NotePhotons(true);
    b.NoteSubsurface(true);
    b.NoteMedia(1, 0.0);
    const std::vector<std::string> expected = {
        "crand", "media method 1", "media method 2", "media jitter", "subsurface",
        "jittered area light", "isosurface evaluate", "radiosity", "photons"};
    EXPECT_EQ(b.Signature().inexactEffects, expected);
}

TEST(SignatureBuilder, DebugListingNamesItems) {
    setenv("POVRAYFC_DEBUG_SIGNATURES", "1", 1);
    SignatureBuilder b;   // reads the variable on Reset
    unsetenv("POVRAYFC_DEBUG_SIGNATURES");
    b.BeginItem("sphere", 12);
    b.SetItemObject(kLowerLeft, kLengths, false, false);
    b.EndItem(ParseItemClass::kObject, 0xabcdefULL, false);
    b.BeginItem("plane", 13);
    b.SetItemObject(kLowerLeft, kLengths, true, false);
    b.EndItem(ParseItemClass::kObject, 0x1ULL, false);
    b.BeginItem("camera", 14);
    b.EndItem(ParseItemClass::kCamera, 0x2ULL, false);
    b.NoteInexact("crand");
    const std::string listing = b.DebugListing();
    EXPECT_NE(listing.find("povrayfc-signature: item 0 object 0000000000abcdef line=12 label=sphere bounds="),
              std::string::npos) << listing;
    EXPECT_NE(listing.find("item 1 object 0000000000000001 line=13 label=plane infinite"),
              std::string::npos) << listing;
    EXPECT_NE(listing.find("item 2 camera 0000000000000002 line=14 label=camera"), std::string::npos)
        << listing;
    EXPECT_NE(listing.find("povrayfc-signature: inexact crand"), std::string::npos);
    EXPECT_NE(listing.find("povrayfc-signature: objects 2"), std::string::npos);

    SignatureBuilder quiet;   // without the variable no items are kept
    quiet.BeginItem("sphere", 1);
    quiet.SetItemObject(kLowerLeft, kLengths, false, false);
    quiet.EndItem(ParseItemClass::kObject, 5, false);
    EXPECT_EQ(quiet.DebugListing().find("item 0"), std::string::npos);
}

TEST(SignatureBuilder, ItemEffectsBecomeNames) {
    SignatureBuilder b;
    b.BeginItem("sphere", 1);
    b.SetItemObject(kLowerLeft, kLengths, false, false);
    b.EndItem(ParseItemClass::kObject, 1, false,
              povrayfc::kEffectIsosurfaceEvaluate | povrayfc::kEffectCrand);
    b.BeginItem("declare", 2);
    b.EndItem(ParseItemClass::kDiscard, 2, false, povrayfc::kEffectMediaJitter);   // ignored
    b.MixGlobal(3, povrayfc::kEffectMediaMethod1);
    const std::vector<std::string> expected = {"crand", "isosurface evaluate", "media method 1"};
    EXPECT_EQ(b.Signature().inexactEffects, expected);
    EXPECT_EQ(povrayfc::InexactEffectNames(0), std::vector<std::string>());
    EXPECT_EQ(povrayfc::InexactEffectNames(1u << 20), std::vector<std::string>{"unknown effect"});
}


TEST(SignatureBuilder, UnitsAreNumberedAcrossItemsAndListed) {
    // Invariant: every unit gets its index in the scene's units, whatever item it belongs
    // to, and the listing says which item it belongs to and what it is.
    SignatureBuilder b;
    b.BeginItem("union", 1);
    b.SetItemObject(kLowerLeft, kLengths, false, false);
    EXPECT_EQ(b.AddUnit(101, 201, kLowerLeft, kLengths, false), 0u);
    EXPECT_EQ(b.AddUnit(102, 202, kLowerLeft, kLengths, false), 1u);
    b.EndItem(ParseItemClass::kObject, 7, false);
    b.BeginItem("plane", 2);
    b.SetItemObject(kLowerLeft, kLengths, true, false);
    EXPECT_EQ(b.AddUnit(103, 203, kLowerLeft, kLengths, true), 2u);
    b.SetUnitContainsCamera(2);
    b.EndItem(ParseItemClass::kObject, 8, false);
    const SceneSignature &s = b.Signature();
    ASSERT_EQ(s.units.size(), 3u);
    EXPECT_EQ(s.units[1].hash, 102u);
    EXPECT_EQ(s.units[1].geometry, 202u);
    EXPECT_FALSE(s.units[1].infinite);
    EXPECT_TRUE(s.units[2].infinite);
    EXPECT_TRUE(s.units[2].containsCamera);
    EXPECT_FALSE(s.units[0].containsCamera);
}

TEST(SignatureBuilder, UnitCapsulesArePaddedAndInfiniteUnitsHaveNone) {
    SignatureBuilder b;
    b.BeginItem("sphere", 1);
    const std::uint32_t u = b.AddUnit(1, 2, kLowerLeft, kLengths, false);
    povrayfc::Capsule c;
    c.a = povrayfc::Vec3{0, 0, 0};
    c.b = povrayfc::Vec3{0, 1, 0};
    c.radius = 0.5;
    b.SetUnitCapsules(u, &c, 1);
    const std::uint32_t w = b.AddUnit(3, 4, kLowerLeft, kLengths, true);
    b.SetUnitCapsules(w, &c, 1);
    ASSERT_EQ(b.Unit(u).capsuleCount, 1);
    EXPECT_GT(b.Unit(u).capsules[0].radius, 0.5);   // float rounding of POV-Ray's own numbers
    EXPECT_LT(b.Unit(u).capsules[0].radius, 0.51);
    EXPECT_EQ(b.Unit(w).capsuleCount, 0);
}
