// Tests for change detection between two frames' signatures: units matched by hash, new
// shapes as hulls, ties' order, full frames.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>

#include "povrayfc/change_detection.h"

namespace povrayfc {
namespace {

FrameSetup Frame() {
    FrameSetup s;
    s.width = s.height = 8;
    s.right = s.bottom = 7;
    return s;
}

// A unit: `hash` is everything about it, `geometry` its shape alone; a unit box at x.
UnitSignature Unit(std::uint64_t hash, std::uint64_t geometry, double x) {
    UnitSignature u;
    u.hash = hash;
    u.geometry = geometry;
    u.bounds = Box{Vec3{x, 0, 0}, Vec3{x + 1, 1, 1}};
    return u;
}

ObjectSignature Item(std::uint64_t hash) {
    ObjectSignature o;
    o.hash = hash;
    return o;
}

// One item per unit, the item's hash that of its unit (enough for the order).
SceneSignature Scene(std::vector<UnitSignature> units) {
    SceneSignature s;
    for (const UnitSignature &u : units) s.objects.push_back(Item(u.hash));
    s.units = std::move(units);
    s.complete = true;
    return s;
}

bool Covers(const std::vector<Hull> &hulls, double x) {
    for (const Hull &h : hulls)
        if (h.box.Contains(Vec3{x + 0.5, 0.5, 0.5})) return true;
    return false;
}

bool Has(const std::vector<std::uint32_t> &v, std::uint32_t x) { return std::find(v.begin(), v.end(), x) != v.end(); }

TEST(ChangeDetection, AMovedUnitIsTestedAtItsNewPlaceAndDirtiesWhatEndedOnIt) {
    const SceneSignature a = Scene({Unit(10, 100, 0), Unit(11, 110, 5)});
    const SceneSignature b = Scene({Unit(10, 100, 0), Unit(12, 120, 6)});
    const FrameChange c = CompareFrames(Frame(), a, Frame(), b, false);
    ASSERT_EQ(c.fullReason, "");
    // Invariant: the unchanged unit continues; the moved one's old self vanished (what ended
    // on it is dirty) and only its new place is a hull (what did not end on the old shape
    // never met it).
    EXPECT_EQ(c.continues[0], 0u);
    EXPECT_EQ(c.continues[1], FrameChange::kNew);
    EXPECT_EQ(c.vanished, std::vector<std::uint32_t>{1});
    EXPECT_EQ(c.hulls.size(), 1u);
    EXPECT_TRUE(Covers(c.hulls, 6));
    EXPECT_FALSE(Covers(c.hulls, 5));
    EXPECT_FALSE(Covers(c.hulls, 0));
}

TEST(ChangeDetection, AChangeOfAppearanceAloneHasNoHull) {
    // Same geometry, another colour: the rays that ended on it are dirty, no other ray can
    // meet it anew.
    const SceneSignature a = Scene({Unit(10, 100, 0), Unit(11, 110, 5)});
    const SceneSignature b = Scene({Unit(10, 100, 0), Unit(13, 110, 5)});
    const FrameChange c = CompareFrames(Frame(), a, Frame(), b, false);
    ASSERT_EQ(c.fullReason, "");
    EXPECT_EQ(c.vanished, std::vector<std::uint32_t>{1});
    EXPECT_TRUE(c.hulls.empty());
    EXPECT_FALSE(c.NothingChanged());
}

TEST(ChangeDetection, AnAppearingUnitIsAHullAndAVanishingOneIsNot) {
    const SceneSignature a = Scene({Unit(10, 100, 0), Unit(11, 110, 5)});
    SceneSignature c1 = a;
    c1.units.push_back(Unit(15, 150, 12));
    c1.objects.push_back(Item(15));
    const FrameChange appeared = CompareFrames(Frame(), a, Frame(), c1, false);
    EXPECT_TRUE(appeared.vanished.empty());
    EXPECT_TRUE(Covers(appeared.hulls, 12));
    const FrameChange gone = CompareFrames(Frame(), c1, Frame(), a, false);
    EXPECT_EQ(gone.vanished, std::vector<std::uint32_t>{2});
    EXPECT_TRUE(gone.hulls.empty());
}

TEST(ChangeDetection, IdenticalUnitsAreMatchedAsAMultiset) {
    // Two identical units and one of them moves: one continues, one vanishes.
    const SceneSignature a = Scene({Unit(10, 100, 0), Unit(10, 100, 0)});
    const SceneSignature b = Scene({Unit(10, 100, 0), Unit(16, 160, 3)});
    const FrameChange c = CompareFrames(Frame(), a, Frame(), b, false);
    EXPECT_NE(c.continues[0], FrameChange::kNew);
    EXPECT_EQ(c.continues[1], FrameChange::kNew);
    EXPECT_EQ(c.vanished.size(), 1u);
    EXPECT_TRUE(Has({0, 1}, c.vanished[0]));
    EXPECT_NE(c.vanished[0], c.continues[0]);
}

// A part of a merge, intersection or difference decides by its solid which surfaces of the
// other parts count: a ray that never ended on it may still depend on it.
UnitSignature Part(std::uint64_t hash, std::uint64_t geometry, double x, std::uint32_t csg = 1) {
    UnitSignature u = Unit(hash, geometry, x);
    u.cutPart = true;
    u.cutGroup = csg;
    return u;
}

TEST(ChangeDetection, AMovedPartOfACsgIsTestedAtItsOldPlaceAndItsNew) {
    // A cutter moved through a wall: where it was, the wall's surface is back.
    const SceneSignature a = Scene({Part(10, 100, 0), Part(11, 110, 5)});
    const SceneSignature b = Scene({Part(10, 100, 0), Part(12, 120, 6)});
    const FrameChange c = CompareFrames(Frame(), a, Frame(), b, false);
    ASSERT_EQ(c.fullReason, "");
    EXPECT_EQ(c.vanished, std::vector<std::uint32_t>{1});
    EXPECT_EQ(c.hulls.size(), 2u);
    EXPECT_TRUE(Covers(c.hulls, 5));
    EXPECT_TRUE(Covers(c.hulls, 6));
    EXPECT_FALSE(Covers(c.hulls, 0));
    // A part that goes reaches every ray through where it was.
    const FrameChange gone = CompareFrames(Frame(), a, Frame(), Scene({Part(10, 100, 0)}), false);
    EXPECT_TRUE(Covers(gone.hulls, 5));
}

TEST(ChangeDetection, AUnitWithCapsulesIsAHullPerCapsuleWithinItsBox) {
    // A cone's narrow half and its wide half, along x in a box from 0 to 10.
    UnitSignature cone;
    cone.bounds = Box{Vec3{0, 0, 0}, Vec3{10, 1, 1}};
    cone.capsuleCount = 2;
    cone.capsules[0] = Capsule{Vec3{0, 0.5, 0.5}, Vec3{5, 0.5, 0.5}, 0.25};
    cone.capsules[1] = Capsule{Vec3{5, 0.5, 0.5}, Vec3{10, 0.5, 0.5}, 0.5};
    Hull hulls[UnitSignature::kMaxCapsules];
    ASSERT_EQ(UnitHulls(cone, hulls), 2);
    // Invariant: each hull holds its capsule, and no more than the unit's box.
    for (const Hull &h : hulls) {
        EXPECT_TRUE(h.hasCapsule);
        EXPECT_GE(h.box.lo.x, -0.01);
        EXPECT_LE(h.box.hi.x, 10.01);
    }
    EXPECT_LE(hulls[0].box.hi.x, 5.26);
    EXPECT_LE(hulls[0].box.hi.y, 0.76);
    EXPECT_GE(hulls[1].box.lo.x, 4.49);
    EXPECT_GE(hulls[1].box.hi.y, 0.99);
    cone.capsuleCount = 0;
    ASSERT_EQ(UnitHulls(cone, hulls), 1);
    EXPECT_FALSE(hulls[0].hasCapsule);
    EXPECT_GE(hulls[0].box.hi.x, 10.0);
}

// A mesh of two triangles side by side (x from 0 to 1 and 1 to 2, in z = 0); the second's
// apex at height `apex`. Its key stands for everything else about it.
UnitSignature Mesh(std::uint64_t hash, double apex, std::uint64_t key = 7) {
    auto faces = std::make_shared<MeshFaces>();
    for (int i = 0; i < 2; ++i) {
        MeshFace f;
        const double h = i == 0 ? 1.0 : apex;
        f.triangle = Triangle{Vec3{double(i), 0, 0}, Vec3{i + 1.0, 0, 0}, Vec3{i + 0.5, h, 0}, 1e-6};
        f.key = std::uint64_t(1000 * h) + 10 * i;
        f.box = Box{Vec3{double(i), 0, 0}, Vec3{i + 1.0, h, 0}};
        f.rimCount = 1;
        f.rims[0] = Box{Vec3{i + 0.49, h - 0.01, 0}, Vec3{i + 0.51, h, 0}};  // near its apex
        faces->push_back(f);
    }
    UnitSignature u = Unit(hash, hash, 0);
    u.bounds = Box{Vec3{0, 0, 0}, Vec3{2, std::max(1.0, apex), 0}};
    u.meshKey = key;
    u.meshFaces = faces;
    return u;
}

TEST(ChangeDetection, AMeshIsTestedAtTheTrianglesThatChangedAndTheRimsOfTheOthers) {
    const SceneSignature a = Scene({Mesh(1, 1.0)});
    const SceneSignature b = Scene({Mesh(2, 1.5)});
    const FrameChange c = CompareFrames(Frame(), a, Frame(), b, false);
    ASSERT_EQ(c.fullReason, "");
    // Invariant: what ended on the old mesh is dirty; the new triangle is a hull shaped like
    // it, and the one kept gives its rim alone.
    EXPECT_EQ(c.vanished, std::vector<std::uint32_t>{0});
    ASSERT_EQ(c.hulls.size(), 2u);
    EXPECT_TRUE(c.hulls[0].hasTriangle && c.hulls[1].hasTriangle);
    EXPECT_LE(c.hulls[0].box.hi.x - c.hulls[0].box.lo.x, 0.03);  // the kept one's rim
    EXPECT_GE(c.hulls[1].box.hi.y, 1.5);                         // the new one
    // A ray straight through the new triangle's box beside the triangle meets no hull;
    // one through the new triangle does, and one through the kept triangle's middle not.
    auto meets = [&](double x, double y) {
        const double o[3] = {x, y, -1}, d[3] = {0, 0, 1};
        Segment s;
        EXPECT_TRUE(MakeSegment(o, d, 10.0, s));
        return std::any_of(c.hulls.begin(), c.hulls.end(), [&](const Hull &h) { return MayMeet(s, h); });
    };
    EXPECT_FALSE(meets(1.05, 1.4));
    EXPECT_TRUE(meets(1.5, 1.4));
    EXPECT_FALSE(meets(0.5, 0.5));
    EXPECT_TRUE(meets(0.5, 0.995));
}

TEST(ChangeDetection, AMeshUnderAnotherKeyKeepsNoTriangleAndOneWithoutFacesIsItsBox) {
    // Another key (its flags, or the unions around it): no triangle is kept.
    FrameChange c = CompareFrames(Frame(), Scene({Mesh(1, 1.0)}), Frame(), Scene({Mesh(2, 1.5, 8)}), false);
    ASSERT_EQ(c.hulls.size(), 2u);
    EXPECT_TRUE(c.hulls[0].hasTriangle && c.hulls[1].hasTriangle);
    EXPECT_GE(c.hulls[0].box.hi.y, 0.99);
    // Without faces: its box.
    UnitSignature plain = Mesh(2, 1.5);
    plain.meshFaces = nullptr;
    c = CompareFrames(Frame(), Scene({Mesh(1, 1.0)}), Frame(), Scene({plain}), false);
    ASSERT_EQ(c.hulls.size(), 1u);
    EXPECT_FALSE(c.hulls[0].hasTriangle);
    EXPECT_GE(c.hulls[0].box.hi.x, 2.0);
}

TEST(ChangeDetection, ATransformedMeshKeepsItsTrianglesOnlyWhileItsBoxStays) {
    // Transformed: POV-Ray rounds its world box both ways, so a kept triangle's hits near
    // that box's faces may be culled otherwise once the box changes.
    UnitSignature before = Mesh(1, 1.0), grown = Mesh(2, 1.5), inside = Mesh(3, 0.8);
    for (UnitSignature *u : {&before, &grown, &inside}) u->meshBoxMustStay = true;
    before.bounds = inside.bounds = Box{Vec3{0, 0, 0}, Vec3{2, 1, 0}};
    FrameChange c = CompareFrames(Frame(), Scene({before}), Frame(), Scene({grown}), false);
    ASSERT_EQ(c.hulls.size(), 1u);
    EXPECT_FALSE(c.hulls[0].hasTriangle);
    c = CompareFrames(Frame(), Scene({before}), Frame(), Scene({inside}), false);
    ASSERT_EQ(c.hulls.size(), 2u);
    EXPECT_TRUE(c.hulls[0].hasTriangle && c.hulls[1].hasTriangle);
    // Moved as well (another key): no triangle is kept, so every one is a hull, whatever
    // its box.
    UnitSignature moved = Mesh(4, 1.5, 8);
    moved.meshBoxMustStay = true;
    c = CompareFrames(Frame(), Scene({before}), Frame(), Scene({moved}), false);
    ASSERT_EQ(c.hulls.size(), 2u);
    EXPECT_TRUE(c.hulls[0].hasTriangle && c.hulls[1].hasTriangle);
}

TEST(ChangeDetection, TheHullsOfWhatAShadowTestMayPassAreListedApart) {
    // Invariant: every hull of a translucent unit is also a translucent hull (the tests
    // opaque blockers answered meet them); no opaque unit's is.
    UnitSignature glass = Unit(12, 120, 6), stone = Unit(14, 140, 9);
    glass.translucent = true;
    stone.opaque = true;
    const SceneSignature a = Scene({Unit(10, 100, 0), Unit(11, 110, 5), Unit(13, 130, 8)});
    const FrameChange c = CompareFrames(Frame(), a, Frame(), Scene({Unit(10, 100, 0), glass, stone}), false);
    ASSERT_EQ(c.fullReason, "");
    EXPECT_EQ(c.hulls.size(), 2u);
    ASSERT_EQ(c.translucentHulls.size(), 1u);
    EXPECT_TRUE(Covers(c.translucentHulls, 6));
    EXPECT_FALSE(Covers(c.translucentHulls, 9));
    // A part of a translucent CSG that moved: where it was, and where it is.
    UnitSignature before = Part(11, 110, 5), after = Part(12, 120, 6);
    before.translucent = after.translucent = true;
    const FrameChange parts = CompareFrames(Frame(), Scene({Part(10, 100, 0), before}), Frame(),
                                            Scene({Part(10, 100, 0), after}), false);
    EXPECT_TRUE(Covers(parts.translucentHulls, 5));
    EXPECT_TRUE(Covers(parts.translucentHulls, 6));
}

TEST(ChangeDetection, APartOfACsgRecolouredAloneIsTestedWhereItIs) {
    // Where another part has no texture, a point of it inside this one takes this one's
    // colour: a ray that ended on that part depends on it.
    const SceneSignature a = Scene({Part(10, 100, 0), Part(11, 110, 5)});
    const FrameChange c = CompareFrames(Frame(), a, Frame(), Scene({Part(10, 100, 0), Part(13, 110, 5)}), false);
    ASSERT_EQ(c.fullReason, "");
    EXPECT_EQ(c.continues[1], FrameChange::kNew);
    EXPECT_EQ(c.vanished, std::vector<std::uint32_t>{1});
    EXPECT_TRUE(Covers(c.hulls, 5));
    EXPECT_FALSE(Covers(c.hulls, 0));
}

TEST(ChangeDetection, ACsgRecolouredWholeHasNoHull) {
    // Every part changed colour: whatever took a part's colour ended on one of them. A part
    // of another CSG that stayed does not count.
    const SceneSignature a = Scene({Part(10, 100, 0), Part(11, 110, 5), Part(20, 200, 9, 2)});
    const SceneSignature b = Scene({Part(12, 100, 0), Part(13, 110, 5), Part(20, 200, 9, 2)});
    const FrameChange c = CompareFrames(Frame(), a, Frame(), b, false);
    ASSERT_EQ(c.fullReason, "");
    EXPECT_EQ(c.vanished.size(), 2u);
    EXPECT_TRUE(c.hulls.empty());
    EXPECT_EQ(c.continues[0], 0u);
    EXPECT_EQ(c.continues[1], 1u);
    // One of its parts changed shape as well: that one is tested where it was and is.
    const FrameChange moved =
        CompareFrames(Frame(), a, Frame(), Scene({Part(12, 100, 0), Part(14, 140, 6), Part(20, 200, 9, 2)}), false);
    EXPECT_EQ(moved.hulls.size(), 2u);
    EXPECT_TRUE(Covers(moved.hulls, 5));
    EXPECT_TRUE(Covers(moved.hulls, 6));
    EXPECT_FALSE(Covers(moved.hulls, 0));
}

TEST(ChangeDetection, ThePartsBesideAPartThatChangedShapeAreNamed) {
    // The box of a difference stays while its cutter moves: a shadow test the box stopped
    // holds only where the cutter never was nor is. The part of another CSG is not named.
    const SceneSignature a = Scene({Part(10, 100, 0), Part(11, 110, 5), Part(20, 200, 9, 2)});
    const FrameChange moved =
        CompareFrames(Frame(), a, Frame(), Scene({Part(10, 100, 0), Part(12, 120, 6), Part(20, 200, 9, 2)}), false);
    EXPECT_EQ(moved.partsBesideAChange, std::vector<std::uint32_t>{0});
    // The whole CSG recoloured: no part changed shape, its opaque parts keep their shadows.
    UnitSignature box = Part(10, 100, 0), cutter = Part(11, 110, 5);
    box.opaque = cutter.opaque = true;
    UnitSignature box2 = box, cutter2 = cutter;
    box2.hash = 13;
    cutter2.hash = 14;
    const FrameChange recoloured = CompareFrames(Frame(), Scene({box, cutter}), Frame(), Scene({box2, cutter2}), false);
    EXPECT_TRUE(recoloured.partsBesideAChange.empty());
    EXPECT_EQ(recoloured.shadowsKept, (std::vector<std::uint8_t>{1, 1}));
    // Recoloured while its cutter moved: the box keeps no shadow by itself.
    UnitSignature moved2 = cutter;
    moved2.hash = 15;
    moved2.geometry = 150;
    moved2.bounds = Box{Vec3{6, 0, 0}, Vec3{7, 1, 1}};
    const FrameChange both = CompareFrames(Frame(), Scene({box, cutter}), Frame(), Scene({box2, moved2}), false);
    EXPECT_EQ(both.shadowsKept, (std::vector<std::uint8_t>{0, 0}));
}

TEST(ChangeDetection, AnUnboundedPartOfACsgThatGoesIsAFullFrame) {
    UnitSignature part = Part(40, 400, 0);
    part.infinite = true;
    part.bounds = Box();
    EXPECT_EQ(CompareFrames(Frame(), Scene({Unit(10, 100, 3), part}), Frame(), Scene({Unit(10, 100, 3)}), false)
                  .fullReason,
              "an unbounded object changed shape");
}

TEST(ChangeDetection, AnUnboundedUnitThatChangesShapeIsAFullFrameAndOneThatChangesColourIsNot) {
    UnitSignature plane = Unit(40, 400, 0);
    plane.infinite = true;
    plane.bounds = Box();
    UnitSignature moved = plane, recoloured = plane;
    moved.hash = 41;
    moved.geometry = 410;
    recoloured.hash = 42;
    const SceneSignature a = Scene({Unit(10, 100, 0), plane});
    EXPECT_EQ(CompareFrames(Frame(), a, Frame(), Scene({Unit(10, 100, 0), moved}), false).fullReason,
              "an unbounded object changed shape");
    const FrameChange c = CompareFrames(Frame(), a, Frame(), Scene({Unit(10, 100, 0), recoloured}), false);
    EXPECT_EQ(c.fullReason, "");
    EXPECT_EQ(c.vanished, std::vector<std::uint32_t>{1});
}

TEST(ChangeDetection, AChangeOfAUnitAroundTheCameraIsAFullFrame) {
    // Camera rays start in its medium: all of them depend on it, whatever they end on.
    UnitSignature room = Unit(50, 500, 0);
    room.containsCamera = true;
    UnitSignature recoloured = room;
    recoloured.hash = 51;
    const SceneSignature a = Scene({room, Unit(10, 100, 3)});
    EXPECT_EQ(CompareFrames(Frame(), a, Frame(), Scene({recoloured, Unit(10, 100, 3)}), false).fullReason,
              "an object around the camera changed");
    // ... also when it appears around the camera, or leaves it.
    const SceneSignature without = Scene({Unit(10, 100, 3)});
    EXPECT_EQ(CompareFrames(Frame(), without, Frame(), a, false).fullReason, "an object around the camera changed");
    EXPECT_EQ(CompareFrames(Frame(), a, Frame(), without, false).fullReason, "an object around the camera changed");
}

TEST(ChangeDetection, NothingAndGlobalChanges) {
    const SceneSignature a = Scene({Unit(10, 100, 0)});
    EXPECT_TRUE(CompareFrames(Frame(), a, Frame(), a, false).NothingChanged());
    SceneSignature b = a;
    b.global = 5;
    EXPECT_EQ(CompareFrames(Frame(), a, Frame(), b, false).fullReason, "global settings or atmosphere changed");
    b = a;
    b.lights = 5;
    EXPECT_EQ(CompareFrames(Frame(), a, Frame(), b, false).fullReason, "light sources changed");
    b = a;
    b.camera = 5;
    EXPECT_TRUE(CompareFrames(Frame(), a, Frame(), b, false).newSequence);
    // Photons: the map depends on every object.
    EXPECT_NE(CompareFrames(Frame(), a, Frame(), Scene({Unit(11, 110, 0)}), true).fullReason, "");
}

TEST(ChangeDetection, TheSameObjectsInAnotherOrderChangeTheOrderOnly) {
    // Invariant: a permutation is no object change, but POV-Ray may meet tied surfaces in
    // another order.
    const SceneSignature a = Scene({Unit(1, 1, 0), Unit(2, 2, 0), Unit(3, 3, 5)});
    const SceneSignature b = Scene({Unit(2, 2, 0), Unit(1, 1, 0), Unit(3, 3, 5)});
    const FrameChange c = CompareFrames(Frame(), a, Frame(), b, false);
    EXPECT_EQ(c.fullReason, "");
    EXPECT_TRUE(c.hulls.empty());
    EXPECT_TRUE(c.vanished.empty());
    EXPECT_TRUE(c.orderChanged);
    EXPECT_FALSE(c.NothingChanged());
}

TEST(ChangeDetection, AnyObjectChangeChangesTheOrderAndNoChangeDoesNot) {
    // Invariant: a change anywhere may reshape the bounding tree; an identical list cannot.
    const SceneSignature a = Scene({Unit(1, 1, 0), Unit(2, 2, 0), Unit(3, 3, 5)});
    const SceneSignature moved = Scene({Unit(1, 1, 0), Unit(2, 2, 0), Unit(4, 4, 9)});
    EXPECT_TRUE(CompareFrames(Frame(), a, Frame(), moved, false).orderChanged);
    const FrameChange same = CompareFrames(Frame(), a, Frame(), a, false);
    EXPECT_FALSE(same.orderChanged);
    EXPECT_TRUE(same.NothingChanged());
}

}  // namespace
}  // namespace povrayfc

namespace povrayfc {
namespace {

TEST(ChangeDetection, ARecolouredUnitKeepsItsShadowsOnlyWhileItStaysOpaque) {
    UnitSignature opaque = Unit(10, 100, 0), recoloured = Unit(11, 100, 0), glassy = Unit(12, 100, 0);
    opaque.opaque = recoloured.opaque = true;
    const SceneSignature a = Scene({opaque});
    const FrameChange kept = CompareFrames(Frame(), a, Frame(), Scene({recoloured}), false);
    ASSERT_EQ(kept.vanished, std::vector<std::uint32_t>{0});
    EXPECT_EQ(kept.shadowsKept, std::vector<std::uint8_t>{1});
    const FrameChange lost = CompareFrames(Frame(), a, Frame(), Scene({glassy}), false);
    EXPECT_EQ(lost.shadowsKept, std::vector<std::uint8_t>{0});
    const FrameChange moved = CompareFrames(Frame(), a, Frame(), Scene({Unit(13, 130, 4)}), false);
    EXPECT_EQ(moved.shadowsKept, std::vector<std::uint8_t>{0});
}

TEST(ChangeDetection, TheBallsAmongTheNewShapesAreTheFramesBlockers) {
    UnitSignature ball = Unit(10, 100, 0), moved = Unit(11, 110, 4), plain = Unit(12, 120, 8);
    ball.hasBall = moved.hasBall = true;
    moved.ball = Ball{Vec3{4, 0, 0}, 1};
    const FrameChange change = CompareFrames(Frame(), Scene({ball, plain}), Frame(), Scene({moved, Unit(13, 130, 9)}), false);
    ASSERT_EQ(change.blockers.size(), 1u);
    EXPECT_EQ(change.blockers[0].ball.centre.x, 4.0);
    EXPECT_EQ(change.blockers[0].unit, 0u);
    // A ball that stayed where it was is no new shape.
    EXPECT_TRUE(CompareFrames(Frame(), Scene({ball}), Frame(), Scene({ball}), false).blockers.empty());
}

// A box kept between its corners with everything else about it `cornerless`.
UnitSignature CornerBox(std::uint64_t hash, std::uint64_t cornerless, Box corners) {
    UnitSignature u = Unit(hash, hash, 0);
    u.bounds = corners;
    u.cornerBox = true;
    u.cornerless = cornerless;
    u.corners = corners;
    return u;
}

bool AnyHullHolds(const std::vector<Hull> &hulls, const Vec3 &p) {
    for (const Hull &h : hulls)
        if (h.box.Contains(p)) return true;
    return false;
}

TEST(ChangeDetection, ABoxThatOnlyGrewKeepsItsIdAndIsTestedWhereTheBoxesDiffer) {
    const UnitSignature bar = CornerBox(10, 77, Box{{0, 0, 0}, {1, 2, 1}});
    const UnitSignature grown = CornerBox(11, 77, Box{{0, 0, 0}, {1, 3, 1}});
    const FrameChange change = CompareFrames(Frame(), Scene({bar}), Frame(), Scene({grown}), false);
    ASSERT_EQ(change.vanished, std::vector<std::uint32_t>{0});
    EXPECT_EQ(change.facesKept, std::vector<std::uint8_t>{1});
    EXPECT_EQ(change.continues, std::vector<std::uint32_t>{0});
    // Invariant: every point in one box and not the other is in a hull; a point well
    // inside both, or outside both, is in none.
    EXPECT_TRUE(AnyHullHolds(change.hulls, Vec3{0.5, 2.5, 0.5}));
    EXPECT_TRUE(AnyHullHolds(change.hulls, Vec3{0.5, 2.0, 0.5}));  // the old top face
    EXPECT_FALSE(AnyHullHolds(change.hulls, Vec3{0.5, 1.0, 0.5}));
    EXPECT_FALSE(AnyHullHolds(change.hulls, Vec3{0.0, 1.0, 0.5}));  // a side face that stays
    EXPECT_FALSE(AnyHullHolds(change.hulls, Vec3{0.5, 3.5, 0.5}));
    // Shrunk, or moved: the place it left is tested too.
    const FrameChange shrunk = CompareFrames(Frame(), Scene({grown}), Frame(), Scene({bar}), false);
    EXPECT_TRUE(AnyHullHolds(shrunk.hulls, Vec3{0.5, 2.5, 0.5}));
    const UnitSignature moved = CornerBox(12, 77, Box{{0.5, 0, 0}, {1.5, 2, 1}});
    const FrameChange slid = CompareFrames(Frame(), Scene({bar}), Frame(), Scene({moved}), false);
    EXPECT_TRUE(AnyHullHolds(slid.hulls, Vec3{0.25, 1, 0.5}));
    EXPECT_TRUE(AnyHullHolds(slid.hulls, Vec3{1.25, 1, 0.5}));
    EXPECT_FALSE(AnyHullHolds(slid.hulls, Vec3{0.75, 1, 0.5}));
}

TEST(ChangeDetection, ABoxThatChangedOtherwiseIsAChangedUnit) {
    const UnitSignature bar = CornerBox(10, 77, Box{{0, 0, 0}, {1, 2, 1}});
    UnitSignature plain = bar;
    plain.cornerBox = false;  // turned, clipped, uv-mapped...
    plain.hash = plain.geometry = 12;
    for (const UnitSignature &now : {CornerBox(11, 78, Box{{0, 0, 0}, {1, 3, 1}}), plain}) {
        const FrameChange change = CompareFrames(Frame(), Scene({bar}), Frame(), Scene({now}), false);
        EXPECT_EQ(change.facesKept, std::vector<std::uint8_t>{0});
        EXPECT_EQ(change.continues, std::vector<std::uint32_t>{FrameChange::kNew});
        EXPECT_TRUE(AnyHullHolds(change.hulls, Vec3{0.5, 1.0, 0.5}));  // its whole new box
    }
}

TEST(ChangeDetection, BarsSharingAKeyArePairedInOrder) {
    const UnitSignature a = CornerBox(10, 77, Box{{0, 0, 0}, {1, 1, 1}});
    const UnitSignature b = CornerBox(11, 77, Box{{5, 0, 0}, {6, 1, 1}});
    const UnitSignature a2 = CornerBox(12, 77, Box{{0, 0, 0}, {1, 2, 1}});
    const UnitSignature b2 = CornerBox(13, 77, Box{{5, 0, 0}, {6, 2, 1}});
    const FrameChange change = CompareFrames(Frame(), Scene({a, b}), Frame(), Scene({a2, b2}), false);
    EXPECT_EQ(change.continues, (std::vector<std::uint32_t>{0, 1}));
    EXPECT_FALSE(AnyHullHolds(change.hulls, Vec3{0.5, 0.5, 0.5}));
    EXPECT_FALSE(AnyHullHolds(change.hulls, Vec3{5.5, 0.5, 0.5}));
}

TEST(ChangeDetection, TheBoxesAmongTheNewShapesAreBlockersToo) {
    UnitSignature box = Unit(10, 100, 0), grown = Unit(11, 110, 4);
    box.hasBlockingBox = grown.hasBlockingBox = true;
    grown.corners = Box{{0, 0, 0}, {2, 5, 1}};
    const FrameChange change = CompareFrames(Frame(), Scene({box}), Frame(), Scene({Unit(12, 120, 8), grown}), false);
    ASSERT_EQ(change.blockers.size(), 1u);
    EXPECT_TRUE(change.blockers[0].isBox);
    EXPECT_EQ(change.blockers[0].box.hi.y, 5.0);
    EXPECT_EQ(change.blockers[0].unit, 1u);
    EXPECT_TRUE(CompareFrames(Frame(), Scene({box}), Frame(), Scene({box}), false).blockers.empty());
}

}  // namespace
}  // namespace povrayfc
