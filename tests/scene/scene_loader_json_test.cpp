// Tests engine/scene/scene_loader_json.cpp: syntax errors with line and column, numbers that
// overflow or underflow, duplicate keys, nesting and object size, each at its JSON path.

#include "scene/scene_loader.h"

#include "scene_loader_test_support.h"

#include <gtest/gtest.h>

#include <string>

namespace substep {
namespace {

using namespace test;

TEST(SceneLoader, TruncatedFileReportsLineAndColumn) {
    const std::string file = kDataDir + "/truncated.json";
    try {
        loadSceneFile(file);
        FAIL() << "no error";
    } catch (const SceneError& e) {
        const std::string what = e.what();
        EXPECT_EQ(what.rfind(file + ": bodies[0]: syntax error at line 6, column 1: ", 0), 0u)
            << what;
        EXPECT_NE(what.find("unexpected end of input"), std::string::npos) << what;
    }
    EXPECT_TRUE(failsAt(R"({"substep_scene": 1, "bodies": [{"shape": )", "bodies[0].shape",
                        "syntax error at line 1, column 43"));
}

TEST(SceneLoader, SyntaxErrors) {
    try {
        parseSceneText("  \n", "t.json");
        FAIL();
    } catch (const SceneError& e) {
        EXPECT_EQ(std::string(e.what()),
                  "t.json: the file is empty (a scene starts with {\"substep_scene\": 1})");
    }
    EXPECT_TRUE(failsAt("{\"substep_scene\": 1,\n \"gravity\": [0 -10, 0]}", "gravity[1]",
                        "syntax error at line 2, column 18"));
    EXPECT_TRUE(
        failsAt(R"({"substep_scene": 1} x)", "top level", "syntax error at line 1, column 22"));
    EXPECT_TRUE(failsAt(R"({"substep_scene": 1,})", "top level", "syntax error"));
    EXPECT_TRUE(failsAt(R"({"substep_scene": 1, "dt": tru})", "dt", "syntax error"));
    EXPECT_TRUE(failsAt("{\"substep_scene\": 1, \"name\": \"a\nb\"}", "name", "syntax error"));
    EXPECT_TRUE(
        failsAt(R"({"substep_scene": 1, /* comment */ "dt": 0.1})", "top level", "syntax error"));
}

TEST(SceneLoader, OverflowingNumbersAreRejectedWhereTheyAre) {
    EXPECT_TRUE(failsAt(withShape(R"("type": "sphere", "radius": 1e999)"), "bodies[0].shape.radius",
                        "number 1e999 overflows a double (line 1, column"));
    EXPECT_TRUE(failsAt(scene(R"("gravity": [0, -1e999, 0])"), "gravity[1]", "overflows"));
    EXPECT_TRUE(failsAt(scene(R"("dt": 1e-400)"), "dt", "too small to represent"));
    // An integer too long for 64 bits reads as a (finite) double and meets the range check.
    EXPECT_TRUE(failsAt(scene(R"("substeps": 123456789012345678901234567890)"), "substeps",
                        "must be an integer in [1, 10000]"));
    EXPECT_TRUE(
        failsAt(scene(R"("substeps": 18446744073709551615)"), "substeps", "must be an integer"));
    EXPECT_TRUE(
        failsAt(scene(R"("substeps": -9223372036854775808)"), "substeps", "must be an integer"));
    // A zero written as 0e-400 or 0.0 is fine.
    EXPECT_NO_THROW(parseSceneText(withBody(kSphere + R"(, "restitution": 0e-400)"), "t.json"));
}

TEST(SceneLoader, DuplicateKeysAreErrors) {
    EXPECT_TRUE(failsAt(withBody(kSphere + R"(, "mass": 1, "mass": 2)"), "bodies[0].mass",
                        "duplicate key"));
    EXPECT_TRUE(failsAt(scene(R"("dt": 0.1, "dt": 0.1)"), "dt", "duplicate key"));
}

TEST(SceneLoader, DeepNestingIsRejected) {
    const std::string deep =
        scene(R"("description": )" + std::string(1000, '[') + std::string(1000, ']'));
    try {
        parseSceneText(deep, "t.json");
        FAIL();
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("nested too deeply"), std::string::npos) << e.what();
    }
}

TEST(SceneLoader, HugeObjectsAreRejected) {
    std::string keys;
    for (int i = 0; i < 1001; ++i)
        keys += ", \"k" + std::to_string(i) + "\": 0";
    EXPECT_TRUE(
        failsAt(scene(R"("camera": {"fov": 1)" + keys + "}"), "camera", "has more than 1000 keys"));
}

}  // namespace
}  // namespace substep
