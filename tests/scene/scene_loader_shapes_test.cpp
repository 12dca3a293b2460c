// Tests engine/scene/scene_loader_shapes.cpp: each shape type's keys and bounds (splines and
// heightfields in detail: shape_keys_test.cpp; meshes: mesh_import_test.cpp).

#include "scene/scene_loader.h"

#include "scene_loader_test_support.h"

#include <gtest/gtest.h>

#include <string>

namespace substep {
namespace {

using namespace test;

TEST(SceneLoader, Shapes) {
    EXPECT_TRUE(failsAt(withBody(R"("mass": 1)"), "bodies[0].shape", "missing (required)"));
    EXPECT_TRUE(failsAt(withBody(R"("shape": "sphere")"), "bodies[0].shape", "must be an object"));
    EXPECT_TRUE(failsAt(withShape(R"("radius": 1)"), "bodies[0].shape.type", "missing"));
    EXPECT_TRUE(failsAt(withShape(R"("type": 1)"), "bodies[0].shape.type", "must be a string"));
    EXPECT_TRUE(failsAt(withShape(R"("type": "cube")"), "bodies[0].shape.type",
                        "unknown shape type \"cube\""));
    // mesh, heightfield and spline keys are tested in mesh_import_test.cpp and shape_keys_test.cpp.
    // sphere
    EXPECT_TRUE(failsAt(withShape(R"("type": "sphere")"), "bodies[0].shape.radius", "missing"));
    // Sizes below 0.1 mm (issue 19: denormal sizes passed and went NaN in the first frames).
    EXPECT_TRUE(failsAt(withShape(R"("type": "box", "size": [1e-320, 1, 1])"), "bodies[0].shape.size[0]",
                        "must be >= 0.0001 (smaller values lose precision or underflow), got 1e-320"));
    EXPECT_TRUE(failsAt(withShape(R"("type": "cylinder", "radius": 0.1, "length": 3.1e-321)"),
                        "bodies[0].shape.length", "must be >= 0.0001"));
    EXPECT_TRUE(failsAt(withShape(R"("type": "capsule", "radius": 5e-5, "length": 1)"),
                        "bodies[0].shape.radius", "must be >= 0.0001"));
    EXPECT_TRUE(failsAt(withShape(R"("type": "sphere", "radius": -1)"), "bodies[0].shape.radius",
                        "must be > 0, got -1"));
    EXPECT_TRUE(failsAt(withShape(R"("type": "sphere", "radius": 0)"), "bodies[0].shape.radius",
                        "must be > 0, got 0"));
    EXPECT_TRUE(failsAt(withShape(R"("type": "sphere", "radius": 2e4)"), "bodies[0].shape.radius",
                        "must be <= 10000"));
    EXPECT_TRUE(failsAt(withShape(R"("type": "sphere", "radius": "1")"), "bodies[0].shape.radius",
                        "must be a number"));
    EXPECT_TRUE(failsAt(withShape(R"("type": "sphere", "radius": 1, "size": [1, 1, 1])"),
                        "bodies[0].shape.size", "unknown key"));
    // box
    EXPECT_TRUE(failsAt(withShape(R"("type": "box")"), "bodies[0].shape.size", "missing"));
    EXPECT_TRUE(failsAt(withShape(R"("type": "box", "size": [1, 1])"), "bodies[0].shape.size",
                        "3 numbers"));
    EXPECT_TRUE(failsAt(withShape(R"("type": "box", "size": [1, -1, 1])"),
                        "bodies[0].shape.size[1]", "must be > 0, got -1"));
    EXPECT_TRUE(failsAt(withShape(R"("type": "box", "size": [1, 1, 0])"), "bodies[0].shape.size[2]",
                        "must be > 0"));
    EXPECT_TRUE(failsAt(withShape(R"("type": "box", "size": [1, 1, 1], "radius": 1)"),
                        "bodies[0].shape.radius", "unknown key"));
    // capsule
    EXPECT_TRUE(failsAt(withShape(R"("type": "capsule", "length": 1)"), "bodies[0].shape.radius",
                        "missing"));
    EXPECT_TRUE(failsAt(withShape(R"("type": "capsule", "radius": 1)"), "bodies[0].shape.length",
                        "missing"));
    EXPECT_TRUE(failsAt(withShape(R"("type": "capsule", "radius": 1, "length": -1)"),
                        "bodies[0].shape.length", "must be >= 0, got -1"));
    EXPECT_TRUE(failsAt(withShape(R"("type": "capsule", "radius": 1, "length": 1e5)"),
                        "bodies[0].shape.length", "must be <= 10000"));
    EXPECT_TRUE(failsAt(withShape(R"("type": "capsule", "radius": -1, "length": 1)"),
                        "bodies[0].shape.radius", "must be > 0"));
    // plane
    EXPECT_TRUE(failsAt(withShape(R"("type": "plane")"), "bodies[0].shape.type",
                        "must be on a static body"));
    EXPECT_TRUE(failsAt(withShape(R"("type": "plane", "normal": [0, 0, 0])", R"("static": true)"),
                        "bodies[0].shape.normal", "must be a non-zero direction"));
    EXPECT_TRUE(failsAt(withShape(R"("type": "plane", "normal": [0, 1])", R"("static": true)"),
                        "bodies[0].shape.normal", "3 numbers"));
    EXPECT_TRUE(failsAt(withShape(R"("type": "plane", "offset": 2e6)", R"("static": true)"),
                        "bodies[0].shape.offset", "must be <= 1e+06"));
    EXPECT_TRUE(failsAt(withShape(R"("type": "plane", "radius": 1)", R"("static": true)"),
                        "bodies[0].shape.radius", "unknown key"));
    EXPECT_TRUE(failsAt(withShape(R"("type": "plane")", R"("static": true, "position": [0, 1, 0])"),
                        "bodies[0].position", "placed by its normal and offset"));
    EXPECT_TRUE(
        failsAt(withShape(R"("type": "plane")", R"("static": true, "orientation": [0, 1, 0, 0])"),
                "bodies[0].orientation", "placed by its normal and offset"));
}

TEST(SceneLoader, CapsuleOfZeroLengthIsASphere) {
    EXPECT_NO_THROW(
        parseSceneText(withShape(R"("type": "capsule", "radius": 1, "length": 0)"), "t.json"));
}

}  // namespace
}  // namespace substep
