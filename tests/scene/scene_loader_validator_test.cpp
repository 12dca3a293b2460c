// Tests engine/scene/scene_loader_validator.cpp: typed reads and their bounds (numbers,
// integers, vectors, quaternions, angles), through the keys that use them.

#include "scene/scene_loader.h"

#include "scene_loader_test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace substep {
namespace {

using namespace test;

TEST(SceneLoader, Gravity) {
    EXPECT_TRUE(
        failsAt(scene(R"("gravity": [0, -10])"), "gravity", "must be an array of 3 numbers"));
    EXPECT_TRUE(failsAt(scene(R"("gravity": [0, -10, 0, 0])"), "gravity", "got an array of 4"));
    EXPECT_TRUE(failsAt(scene(R"("gravity": -10)"), "gravity", "got -10"));
    EXPECT_TRUE(failsAt(scene(R"("gravity": [0, "-10", 0])"), "gravity[1]",
                        "must be a number, got the string \"-10\""));
    EXPECT_TRUE(failsAt(scene(R"("gravity": [0, null, 0])"), "gravity[1]", "got null"));
    EXPECT_TRUE(failsAt(scene(R"("gravity": [0, true, 0])"), "gravity[1]", "got true"));
    EXPECT_TRUE(failsAt(scene(R"("gravity": [0, -1e5, 0])"), "gravity[1]", "must be >= -10000"));
    EXPECT_TRUE(failsAt(scene(R"("gravity": [2e4, 0, 0])"), "gravity[0]",
                        "must be <= 10000 (a sanity bound"));
}

TEST(SceneLoader, StepSettings) {
    EXPECT_TRUE(failsAt(scene(R"("dt": 0)"), "dt", "must be in (0, 1], got 0"));
    EXPECT_TRUE(failsAt(scene(R"("dt": -0.01)"), "dt", "must be in (0, 1], got -0.01"));
    EXPECT_TRUE(failsAt(scene(R"("dt": 1.5)"), "dt", "must be in (0, 1], got 1.5"));
    EXPECT_TRUE(failsAt(scene(R"("dt": "1/60")"), "dt", "must be a number"));
    EXPECT_NO_THROW(parseSceneText(scene(R"("dt": 1)"), "t.json"));

    EXPECT_TRUE(
        failsAt(scene(R"("substeps": 0)"), "substeps", "must be an integer in [1, 10000], got 0"));
    EXPECT_TRUE(failsAt(scene(R"("substeps": 10001)"), "substeps", "got 10001"));
    EXPECT_TRUE(failsAt(scene(R"("substeps": 2.5)"), "substeps",
                        "must be an integer in [1, 10000], got 2.5"));
    EXPECT_TRUE(failsAt(scene(R"("substeps": "20")"), "substeps", "got the string \"20\""));
    EXPECT_TRUE(failsAt(scene(R"("substeps": 1e10)"), "substeps", "got 1e+10"));
    EXPECT_NO_THROW(parseSceneText(scene(R"("substeps": 10000, "iterations": 1000)"), "t.json"));

    EXPECT_TRUE(failsAt(scene(R"("iterations": 0)"), "iterations",
                        "must be an integer in [1, 1000], got 0"));
    EXPECT_TRUE(failsAt(scene(R"("iterations": 1001)"), "iterations", "got 1001"));
    EXPECT_TRUE(failsAt(scene(R"("iterations": -3)"), "iterations", "got -3"));
    EXPECT_TRUE(failsAt(scene(R"("iterations": false)"), "iterations", "got false"));
}

TEST(SceneLoader, WholeFloatsCountAsIntegers) {
    const auto s = parseSceneText(scene(R"("substeps": 20.0, "iterations": 1e1)"), "t.json");
    EXPECT_EQ(s.substeps, 20);
    EXPECT_EQ(s.iterations, 10);
}

TEST(SceneLoader, QuaternionsAreNormalised) {
    const auto s = parseSceneText(withBody(kSphere + R"(, "orientation": [1, 2, 3, 4])"), "t.json");
    const Quat& q = s.bodies[0].def.orientation;
    const double n = std::sqrt(30.0);
    EXPECT_NEAR(q.w(), 1 / n, 1e-15);
    EXPECT_NEAR(q.x(), 2 / n, 1e-15);
    EXPECT_NEAR(q.y(), 3 / n, 1e-15);
    EXPECT_NEAR(q.z(), 4 / n, 1e-15);
    EXPECT_NEAR(q.norm(), 1.0, 1e-15);
    // Huge components do not overflow the length.
    const auto big =
        parseSceneText(withBody(kSphere + R"(, "orientation": [0, 1e300, 0, 0])"), "t.json");
    EXPECT_NEAR(big.bodies[0].def.orientation.x(), 1.0, 1e-15);
}

TEST(SceneLoader, AngleBoundsAcceptExactPi) {
    EXPECT_NO_THROW(
        parseSceneText(hinge(R"("limits": [-3.141592653589793, 3.141592653589793])"), "t.json"));
    EXPECT_NO_THROW(
        parseSceneText(spherical(R"("swing_limit": 0, "twist_limits": [0, 0])"), "t.json"));
    EXPECT_NO_THROW(parseSceneText(hinge(R"("limits": [0.5, 0.5])"), "t.json"));  // lo == hi locks
}

}  // namespace
}  // namespace substep
