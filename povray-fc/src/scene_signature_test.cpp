#include <gtest/gtest.h>

#include <thread>
#include <vector>

#include "povrayfc/scene_signature.h"

using povrayfc::ObjectSignature;
using povrayfc::PublishSceneSignature;
using povrayfc::SceneSignature;
using povrayfc::TakeSceneSignature;

namespace {

SceneSignature MakeSignature(std::uint64_t camera, int objects) {
    SceneSignature s;
    s.camera = camera;
    s.lights = camera + 1;
    s.global = camera + 2;
    for (int i = 0; i < objects; ++i) {
        ObjectSignature o;
        o.hash = camera * 100 + i;
        o.bounds.lo = {double(i), 0, 0};
        o.bounds.hi = {double(i) + 1, 1, 1};
        s.objects.push_back(o);
    }
    s.inexactEffects.push_back("crand");
    s.complete = true;
    return s;
}

}  // namespace

TEST(SceneSignature, TakeWithoutPublishFails) {
    int key = 0;
    SceneSignature out;
    EXPECT_FALSE(TakeSceneSignature(&key, out));
}

TEST(SceneSignature, PublishThenTakeMovesItOnce) {
    int key = 0;
    PublishSceneSignature(&key, MakeSignature(10, 3));
    SceneSignature out;
    ASSERT_TRUE(TakeSceneSignature(&key, out));
    EXPECT_EQ(out.camera, 10u);
    EXPECT_EQ(out.lights, 11u);
    EXPECT_EQ(out.global, 12u);
    ASSERT_EQ(out.objects.size(), 3u);
    EXPECT_EQ(out.objects[2].hash, 1002u);
    EXPECT_EQ(out.objects[2].bounds.lo.x, 2.0);
    ASSERT_EQ(out.inexactEffects.size(), 1u);
    EXPECT_EQ(out.inexactEffects[0], "crand");
    EXPECT_TRUE(out.complete);
    // Taken: a second take finds nothing.
    SceneSignature again;
    EXPECT_FALSE(TakeSceneSignature(&key, again));
}

TEST(SceneSignature, KeyedByScene) {
    int sceneA = 0, sceneB = 0;
    PublishSceneSignature(&sceneA, MakeSignature(1, 1));
    SceneSignature out;
    EXPECT_FALSE(TakeSceneSignature(&sceneB, out));   // never another scene's signature
    PublishSceneSignature(&sceneB, MakeSignature(2, 2));
    ASSERT_TRUE(TakeSceneSignature(&sceneB, out));
    EXPECT_EQ(out.camera, 2u);
    ASSERT_TRUE(TakeSceneSignature(&sceneA, out));
    EXPECT_EQ(out.camera, 1u);
}

TEST(SceneSignature, NewerPublishReplacesOlder) {
    int key = 0;
    PublishSceneSignature(&key, MakeSignature(1, 1));
    PublishSceneSignature(&key, MakeSignature(5, 2));   // next frame's parse of the same scene
    SceneSignature out;
    ASSERT_TRUE(TakeSceneSignature(&key, out));
    EXPECT_EQ(out.camera, 5u);
    EXPECT_EQ(out.objects.size(), 2u);
    EXPECT_FALSE(TakeSceneSignature(&key, out));
}

TEST(SceneSignature, BoundedNumberWaiting) {
    // Signatures nobody takes do not pile up: the oldest are dropped, the newest kept.
    std::vector<int> keys(50);
    for (size_t i = 0; i < keys.size(); ++i) PublishSceneSignature(&keys[i], MakeSignature(i, 0));
    SceneSignature out;
    EXPECT_FALSE(TakeSceneSignature(&keys[0], out));
    ASSERT_TRUE(TakeSceneSignature(&keys.back(), out));
    EXPECT_EQ(out.camera, keys.size() - 1);
    for (int &k : keys) TakeSceneSignature(&k, out);   // leave nothing behind for other tests
}

TEST(SceneSignature, PublishAndTakeFromOtherThreads) {
    int key = 0;
    std::thread parser([&] { PublishSceneSignature(&key, MakeSignature(77, 4)); });
    parser.join();
    SceneSignature out;
    bool taken = false;
    std::thread renderer([&] { taken = TakeSceneSignature(&key, out); });
    renderer.join();
    ASSERT_TRUE(taken);
    EXPECT_EQ(out.camera, 77u);
    EXPECT_EQ(out.objects.size(), 4u);
}
