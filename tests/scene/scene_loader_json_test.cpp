// Tests engine/scene/scene_loader_json.cpp: syntax errors with line and column, numbers that
// overflow or underflow, duplicate keys, nesting, object and array size and the document's memory,
// each at its JSON path, and the top level's checks made while parsing (scene_loader.cpp).

#include "scene/scene_loader.h"
#include "scene/scene_loader_json.h"

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

/// `count` copies of `element` joined by commas.
std::string repeated(const std::string& element, std::size_t count) {
    std::string out;
    out.reserve(count * (element.size() + 1));
    for (std::size_t i = 0; i < count; ++i) {
        if (i > 0) out += ',';
        out += element;
    }
    return out;
}

// Each case below ends in text the parser never reaches (a syntax error): before the checks
// were made while parsing, that syntax error was reported, after the whole document was built.
const std::string kNeverRead = ", \"x\": oops";

TEST(SceneLoader, ArraysPastTheFormatsLongestFailAtTheFirstElementTooMany) {
    EXPECT_TRUE(failsAt(scene(R"("bodies": [)" + repeated("{}", 100001) + "]" + kNeverRead),
                        "bodies",
                        "has more than 100000 bodies (a sanity bound against absurd values)"));
    EXPECT_TRUE(failsAt(scene(R"("joints": [)" + repeated("3", 100001) + "]" + kNeverRead),
                        "joints", "has more than 100000 joints"));
    EXPECT_TRUE(failsAt(scene(R"("description": [[], [)" + repeated("0", 100001) + "]]" + kNeverRead),
                        "description[1]", "has more than 100000 elements"));
    // The spline's own message, which its reader gave before the parser had a cap.
    const std::string points = repeated("[0, 0, 0]", 100001);
    EXPECT_TRUE(failsAt(
        withBody(R"("static": true, "shape": {"type": "spline", "radius": 0.1, "points": [)" + points +
                 "]}"),
        "bodies[0].shape.points",
        "has more than 100000 points (a sanity bound against absurd values)"));
    // 100000 is allowed.
    EXPECT_TRUE(failsAt(scene(R"("bodies": [)" + repeated("3", 100000) + "]"), "bodies[0]",
                        "must be a body object, got 3"));
}

TEST(SceneLoader, DocumentsTooLargeForMemoryFailWhileRead) {
    // The bound is 512 MiB; a smaller one shows the rule without a file that large. Each value
    // counts its 16-byte slot, a container its heap block, a member its key.
    const std::string text = "[" + repeated("[]", 20000) + "]";
    EXPECT_NO_THROW(scene_loader::readJsonDocument(text, "t.json", nullptr, 2u << 20));
    try {
        scene_loader::readJsonDocument(text + kNeverRead, "t.json", nullptr, 1u << 20);
        FAIL() << "no error";
    } catch (const SceneError& e) {
        EXPECT_EQ(std::string(e.what()),
                  "t.json: top level: too large: the document would take more than 1 MiB of "
                  "memory once read (a 4096 x 4096 heightfield, the largest thing a scene holds, "
                  "takes 256 MiB)");
    }
    EXPECT_EQ(scene_loader::kMaxDocumentBytes, std::size_t{512} << 20);
}

TEST(SceneLoader, TopLevelProblemsFailWhereTheParserMeetsThem) {
    // An unknown key once the version has been read.
    EXPECT_TRUE(failsAt(R"({"substep_scene": 1, "bodis": [)" + kNeverRead, "bodis",
                        "unknown key (did you mean \"bodies\"?)"));
    // An unknown key before the version: reported when the version turns out right...
    EXPECT_TRUE(failsAt(R"({"bodis": [], "zzz": 1, "substep_scene": 1)" + kNeverRead, "bodis",
                        "unknown key (did you mean \"bodies\"?)"));
    // ... and the version's own message when it is wrong, as the version is checked first.
    EXPECT_TRUE(failsAt(R"({"bodis": [], "substep_scene": 3)" + kNeverRead, "substep_scene",
                        "unsupported version 3 (this build reads version 1)"));
    EXPECT_TRUE(failsAt(R"({"substep_scene": "1")" + kNeverRead, "substep_scene",
                        "must be 1, got the string \"1\""));
    // A document that is not an object fails at its first bracket.
    EXPECT_TRUE(failsAt("[1, 2" + kNeverRead, "top level", "must be a JSON object, got an array"));
    // Without a version the rest is read and the validator reports the missing version.
    EXPECT_TRUE(failsAt(R"({"bodis": []})", "substep_scene", "missing"));
}

}  // namespace
}  // namespace substep
