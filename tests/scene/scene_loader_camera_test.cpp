// Tests engine/scene/scene_loader_camera.cpp: the camera's keys and bounds.

#include "scene/scene_loader.h"

#include "scene_loader_test_support.h"

#include <gtest/gtest.h>

#include <string>

namespace substep {
namespace {

using namespace test;

TEST(SceneLoader, Camera) {
    EXPECT_TRUE(failsAt(scene(R"("camera": [0, 1, 2])"), "camera", "must be an object"));
    EXPECT_TRUE(failsAt(scene(R"("camera": {"up": [0, 1, 0]})"), "camera.up", "unknown key"));
    EXPECT_TRUE(
        failsAt(scene(R"("camera": {"fov": 0})"), "camera.fov", "must be in (0, pi), got 0"));
    EXPECT_TRUE(failsAt(scene(R"("camera": {"fov": 3.141592653589793})"), "camera.fov",
                        "must be in (0, pi)"));
    EXPECT_TRUE(failsAt(scene(R"("camera": {"fov": 60})"), "camera.fov", "got 60"));
    EXPECT_TRUE(
        failsAt(scene(R"("camera": {"position": [0, 1]})"), "camera.position", "3 numbers"));
    EXPECT_TRUE(failsAt(scene(R"("camera": {"target": [0, 2e6, 0]})"), "camera.target[1]",
                        "must be <= 1e+06"));
    EXPECT_TRUE(failsAt(scene(R"("camera": {"position": [1, 1, 1], "target": [1, 1, 1]})"),
                        "camera.target", "must differ from its position"));
    const auto s = parseSceneText(scene(R"("camera": {"fov": 1.2})"), "t.json");
    ASSERT_TRUE(s.camera.has_value());
    EXPECT_EQ(s.camera->fov, 1.2);
    EXPECT_EQ(s.camera->position, SceneCamera{}.position);
}

}  // namespace
}  // namespace substep
