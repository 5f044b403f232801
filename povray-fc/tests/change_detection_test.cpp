// Tests for change detection between two frames' signatures, including CSG children.
#include <gtest/gtest.h>

#include "povrayfc/change_detection.h"

namespace povrayfc {
namespace {

FrameSetup Frame() {
    FrameSetup s;
    s.width = s.height = 8;
    s.right = s.bottom = 7;
    return s;
}

ChildSignature Child(std::uint64_t hash, double x, bool light = false) {
    ChildSignature c;
    c.hash = hash;
    c.bounds = Box{Vec3{x, 0, 0}, Vec3{x + 1, 1, 1}};
    c.isLight = light;
    if (light) {
        c.infinite = true;
        c.bounds = Box();
    }
    return c;
}

ObjectSignature Csg(std::uint64_t hash, std::uint64_t shell, std::vector<ChildSignature> children) {
    ObjectSignature o;
    o.hash = hash;
    o.shell = shell;
    o.children = std::move(children);
    for (const ChildSignature &c : o.children)
        if (!c.isLight) o.bounds.Grow(c.bounds);
    return o;
}

SceneSignature Scene(std::vector<ObjectSignature> objects) {
    SceneSignature s;
    s.objects = std::move(objects);
    s.complete = true;
    return s;
}

bool Covers(const std::vector<Hull> &hulls, double x) {
    for (const Hull &h : hulls)
        if (h.box.Contains(Vec3{x + 0.5, 0.5, 0.5})) return true;
    return false;
}

TEST(ChangeDetection, MovedChildOfAUnionDirtiesOnlyThatChild) {
    const SceneSignature a = Scene({Csg(1, 77, {Child(10, 0), Child(11, 5)})});
    const SceneSignature b = Scene({Csg(2, 77, {Child(10, 0), Child(12, 6)})});
    const FrameChange c = CompareFrames(Frame(), a, Frame(), b, false);
    ASSERT_EQ(c.fullReason, "");
    // Invariant: the unchanged child's place is not dirty; the moved one's old and new are.
    EXPECT_EQ(c.hulls.size(), 2u);
    EXPECT_FALSE(Covers(c.hulls, 0));
    EXPECT_TRUE(Covers(c.hulls, 5));
    EXPECT_TRUE(Covers(c.hulls, 6));
}

TEST(ChangeDetection, ChangedShellDirtiesTheWholeObject) {
    // Same children, another texture or transform on the union: everything it covers.
    const SceneSignature a = Scene({Csg(1, 77, {Child(10, 0), Child(11, 5)})});
    const SceneSignature b = Scene({Csg(2, 78, {Child(10, 0), Child(11, 5)})});
    const FrameChange c = CompareFrames(Frame(), a, Frame(), b, false);
    ASSERT_EQ(c.fullReason, "");
    EXPECT_TRUE(Covers(c.hulls, 0));
    EXPECT_TRUE(Covers(c.hulls, 5));
}

TEST(ChangeDetection, LightOfALightGroupDirtiesWhatItLights) {
    const SceneSignature a = Scene({Csg(1, 77, {Child(10, 0), Child(11, 5), Child(20, 0, true)}),
                                    Csg(3, 99, {Child(30, 20), Child(31, 21)})});
    const SceneSignature b = Scene({Csg(2, 77, {Child(10, 0), Child(11, 5), Child(21, 0, true)}),
                                    Csg(3, 99, {Child(30, 20), Child(31, 21)})});
    const FrameChange c = CompareFrames(Frame(), a, Frame(), b, false);
    // Invariant: not a full frame; the group's objects are dirty, the other object is not.
    ASSERT_EQ(c.fullReason, "");
    EXPECT_TRUE(Covers(c.hulls, 0));
    EXPECT_TRUE(Covers(c.hulls, 5));
    EXPECT_FALSE(Covers(c.hulls, 20));
}

TEST(ChangeDetection, UnboundedChildOrObjectMakesAFullFrame) {
    ChildSignature plane = Child(40, 0);
    plane.infinite = true;
    plane.bounds = Box();
    ObjectSignature before = Csg(1, 77, {Child(10, 0), plane});
    before.infinite = true;
    ChildSignature plane2 = plane;
    plane2.hash = 41;
    ObjectSignature after = Csg(2, 77, {Child(10, 0), plane2});
    after.infinite = true;
    const FrameChange c = CompareFrames(Frame(), Scene({before}), Frame(), Scene({after}), false);
    EXPECT_EQ(c.fullReason, "an unbounded object changed");
}

TEST(ChangeDetection, NothingAndGlobalChanges) {
    const SceneSignature a = Scene({Csg(1, 77, {Child(10, 0)})});
    EXPECT_TRUE(CompareFrames(Frame(), a, Frame(), a, false).NothingChanged());
    SceneSignature b = a;
    b.global = 5;
    EXPECT_EQ(CompareFrames(Frame(), a, Frame(), b, false).fullReason, "global settings or atmosphere changed");
    b = a;
    b.camera = 5;
    EXPECT_TRUE(CompareFrames(Frame(), a, Frame(), b, false).newSequence);
}

}  // namespace
}  // namespace povrayfc

namespace povrayfc {
namespace {

ObjectSignature Plain(std::uint64_t hash, double x) {
    ObjectSignature o;
    o.hash = hash;
    o.bounds = Box{Vec3{x, 0, 0}, Vec3{x + 1, 1, 1}};
    return o;
}

TEST(ChangeDetection, TheSameObjectsInAnotherOrderChangeTheOrderOnly) {
    // Invariant: a permutation is no object change, but POV-Ray may meet tied surfaces in
    // another order.
    const SceneSignature a = Scene({Plain(1, 0), Plain(2, 0), Plain(3, 5)});
    const SceneSignature b = Scene({Plain(2, 0), Plain(1, 0), Plain(3, 5)});
    const FrameChange c = CompareFrames(Frame(), a, Frame(), b, false);
    EXPECT_EQ(c.fullReason, "");
    EXPECT_TRUE(c.hulls.empty());
    EXPECT_TRUE(c.orderChanged);
    EXPECT_FALSE(c.NothingChanged());
}

TEST(ChangeDetection, AnyObjectChangeChangesTheOrderAndNoChangeDoesNot) {
    // Invariant: a change anywhere may reshape the bounding tree; an identical list cannot.
    const SceneSignature a = Scene({Plain(1, 0), Plain(2, 0), Plain(3, 5)});
    const SceneSignature moved = Scene({Plain(1, 0), Plain(2, 0), Plain(4, 9)});
    EXPECT_TRUE(CompareFrames(Frame(), a, Frame(), moved, false).orderChanged);
    const FrameChange same = CompareFrames(Frame(), a, Frame(), a, false);
    EXPECT_FALSE(same.orderChanged);
    EXPECT_TRUE(same.NothingChanged());
}

}  // namespace
}  // namespace povrayfc
