#pragma once
// Shared by the scene loader tests (tests/scene/scene_loader*_test.cpp): failsAt, which checks
// that a text fails with one line at an exact JSON path, and builders of small scene texts.

#include "scene/scene_loader.h"

#include <gtest/gtest.h>

#include <exception>
#include <string>

#ifndef SUBSTEP_TEST_DATA_DIR
#define SUBSTEP_TEST_DATA_DIR "tests/data/scenes"
#endif

namespace substep::test {

inline const std::string kDataDir = SUBSTEP_TEST_DATA_DIR;

/// Passes when parsing `text` throws a SceneError whose one-line message is
/// `t.json: PATH: ...` and contains `fragment`.
inline ::testing::AssertionResult failsAt(const std::string& text, const std::string& path,
                                          const std::string& fragment = "") {
    try {
        parseSceneText(text, "t.json");
    } catch (const SceneError& error) {
        const std::string what = error.what();
        const std::string prefix = "t.json: " + path + ": ";
        if (what.rfind(prefix, 0) != 0) {
            return ::testing::AssertionFailure()
                   << "expected \"" << prefix << "...\", got \"" << what << "\"";
        }
        if (what.find(fragment) == std::string::npos) {
            return ::testing::AssertionFailure()
                   << "expected \"" << fragment << "\" in \"" << what << "\"";
        }
        if (what.find('\n') != std::string::npos) {
            return ::testing::AssertionFailure() << "message spans lines: \"" << what << "\"";
        }
        if (error.path() != path) {
            return ::testing::AssertionFailure() << "path() is \"" << error.path() << "\"";
        }
        return ::testing::AssertionSuccess();
    } catch (const std::exception& other) {
        return ::testing::AssertionFailure() << "threw something else: " << other.what();
    }
    return ::testing::AssertionFailure() << "no error for " << text;
}

inline std::string scene(const std::string& members) {
    return R"({"substep_scene": 1)" + (members.empty() ? "" : ", " + members) + "}";
}
/// A scene with one body made of `members` (add a shape yourself if you need one).
inline std::string withBody(const std::string& members) {
    return scene(R"("bodies": [{)" + members + "}]");
}
inline const std::string kSphere = R"("shape": {"type": "sphere", "radius": 0.5})";
inline std::string withShape(const std::string& shapeMembers, const std::string& more = "") {
    return withBody(R"("shape": {)" + shapeMembers + "}" + (more.empty() ? "" : ", " + more));
}
/// A scene with bodies "a" (static) and "b" and one joint made of `members`.
inline std::string withJoint(const std::string& members) {
    return scene(
        R"("bodies": [{"name": "a", "static": true, "shape": {"type": "box", "size": [1, 1, 1]}},
                               {"name": "b", "shape": {"type": "sphere", "radius": 0.5}}],
                    "joints": [{)" +
        members + "}]");
}
inline std::string hinge(const std::string& more) {
    return withJoint(R"("type": "hinge", "body0": "a", "body1": "b", )" + more);
}
inline std::string prismatic(const std::string& more) {
    return withJoint(R"("type": "prismatic", "body0": "a", "body1": "b", )" + more);
}
inline std::string spherical(const std::string& more) {
    return withJoint(R"("type": "spherical", "body0": "a", "body1": "b", )" + more);
}
inline std::string distance(const std::string& more) {
    return withJoint(R"("type": "distance", "body0": "a", "body1": "b", )" + more);
}

}  // namespace substep::test
