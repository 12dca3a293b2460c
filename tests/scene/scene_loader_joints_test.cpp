// Tests engine/scene/scene_loader_joints.cpp: joint types and the keys each uses, bodies,
// names, frames, limits, drives, compliances and damping, and the JointDef values they map onto.

#include "scene/scene_loader.h"

#include "scene_loader_test_support.h"

#include <gtest/gtest.h>

#include <string>

namespace substep {
namespace {

using namespace test;

TEST(SceneLoader, JointTypeAndKeys) {
    EXPECT_TRUE(failsAt(withJoint(R"("body0": "a", "body1": "b")"), "joints[0].type", "missing"));
    EXPECT_TRUE(failsAt(withJoint(R"("type": "weld", "body1": "b")"), "joints[0].type",
                        "unknown joint type \"weld\""));
    EXPECT_TRUE(
        failsAt(withJoint(R"("type": 3, "body1": "b")"), "joints[0].type", "must be a string"));
    EXPECT_TRUE(failsAt(hinge(R"("axsi0": [0, 1, 0])"), "joints[0].axsi0",
                        "unknown key (did you mean \"axis0\"?)"));
    EXPECT_TRUE(failsAt(hinge(R"("stiffness": 1)"), "joints[0].stiffness", "unknown key"));
    EXPECT_TRUE(failsAt(withJoint(R"("type": "hinge", "body1": "b", "name": "h", "name2": 1)"),
                        "joints[0].name2", "unknown key"));
}

TEST(SceneLoader, KeysThatDoNotApplyToTheJointType) {
    EXPECT_TRUE(failsAt(hinge(R"("max_distance": 1)"), "joints[0].max_distance",
                        "does not apply to a hinge joint (only to distance joints)"));
    EXPECT_TRUE(failsAt(distance(R"("limits": [0, 1])"), "joints[0].limits",
                        "does not apply to a distance joint (only to hinge and prismatic joints)"));
    EXPECT_TRUE(failsAt(distance(R"("axis0": [0, 1, 0])"), "joints[0].axis0",
                        "does not apply to a distance joint"));
    EXPECT_TRUE(failsAt(distance(R"("normal1": [1, 0, 0])"), "joints[0].normal1",
                        "does not apply to a distance joint"));
    EXPECT_TRUE(failsAt(prismatic(R"("target_angle": 1)"), "joints[0].target_angle",
                        "does not apply to a prismatic joint"));
    EXPECT_TRUE(failsAt(prismatic(R"("target_velocity": 1)"), "joints[0].target_velocity",
                        "does not apply to a prismatic joint"));
    EXPECT_TRUE(failsAt(hinge(R"("target_offset": 1)"), "joints[0].target_offset",
                        "does not apply to a hinge joint"));
    EXPECT_TRUE(
        failsAt(hinge(R"("swing_limit": 1)"), "joints[0].swing_limit", "only to spherical joints"));
    EXPECT_TRUE(failsAt(hinge(R"("twist_limits": [0, 1])"), "joints[0].twist_limits",
                        "only to spherical joints"));
    EXPECT_TRUE(failsAt(hinge(R"("twist_compliance": 1)"), "joints[0].twist_compliance",
                        "only to spherical joints"));
    EXPECT_TRUE(failsAt(spherical(R"("limits": [0, 1])"), "joints[0].limits",
                        "does not apply to a spherical joint"));
    EXPECT_TRUE(failsAt(spherical(R"("drive_compliance": 0)"), "joints[0].drive_compliance",
                        "does not apply to a spherical joint"));
    EXPECT_TRUE(
        failsAt(withJoint(R"("type": "fixed", "body1": "b", "limit_compliance": 0)"),
                "joints[0].limit_compliance",
                "does not apply to a fixed joint (only to hinge, spherical and prismatic joints)"));
    EXPECT_TRUE(failsAt(withJoint(R"("type": "fixed", "body1": "b", "max_distance": 0)"),
                        "joints[0].max_distance", "does not apply to a fixed joint"));
    // And keys every type shares are accepted by each.
    for (const char* type : {"distance", "fixed", "hinge", "spherical", "prismatic"}) {
        EXPECT_NO_THROW(parseSceneText(
            withJoint(std::string(R"("type": ")") + type +
                      R"(", "name": "j", "body0": "a", "body1": "b", "anchor0": [0, 0, 0],
                          "anchor1": [0, 0, 0], "compliance": 0, "collide": true,
                          "damping": {"linear": 1, "angular": 1})"),
            "t.json"))
            << type;
    }
}

TEST(SceneLoader, JointBodies) {
    EXPECT_TRUE(failsAt(withJoint(R"("type": "fixed", "body1": "c")"), "joints[0].body1",
                        "no body named \"c\""));
    EXPECT_TRUE(failsAt(withJoint(R"("type": "fixed", "body0": "bb")"), "joints[0].body0",
                        "no body named \"bb\" (did you mean \"b\"?)"));
    EXPECT_TRUE(failsAt(withJoint(R"("type": "fixed", "body1": 1)"), "joints[0].body1",
                        "must be a string"));
    EXPECT_TRUE(failsAt(withJoint(R"("type": "fixed", "body1": "")"), "joints[0].body1",
                        "must name a body"));
    EXPECT_TRUE(failsAt(withJoint(R"("type": "fixed")"), "joints[0]",
                        "both ends of the joint are the world"));
    EXPECT_TRUE(
        failsAt(withJoint(R"("type": "fixed", "body0": "world")"), "joints[0].body0", "both ends"));
    EXPECT_TRUE(failsAt(withJoint(R"("type": "fixed", "body0": "world", "body1": "world")"),
                        "joints[0].body1", "both ends"));
    EXPECT_TRUE(failsAt(withJoint(R"("type": "fixed", "body0": "b", "body1": "b")"),
                        "joints[0].body1", "joins body \"b\" to itself"));
    // Unnamed bodies cannot be referred to.
    EXPECT_TRUE(failsAt(
        scene(R"("bodies": [{)" + kSphere + R"(}], "joints": [{"type": "fixed", "body1": "0"}])"),
        "joints[0].body1", "no body named \"0\""));
}

TEST(SceneLoader, JointsMayReferenceTheWorldOnEitherSide) {
    const auto s =
        parseSceneText(withJoint(R"("type": "fixed", "body0": "b", "body1": "world")"), "t.json");
    EXPECT_EQ(s.joints[0].body0, "b");
    EXPECT_EQ(s.joints[0].body1, "world");
    const auto t = parseSceneText(withJoint(R"("type": "fixed", "body0": "b")"), "t.json");
    EXPECT_TRUE(t.joints[0].body1.empty());
}

TEST(SceneLoader, JointNames) {
    EXPECT_TRUE(failsAt(distance(R"("name": 1)"), "joints[0].name", "must be a string"));
    EXPECT_TRUE(failsAt(distance(R"("name": "")"), "joints[0].name", "must not be empty"));
    EXPECT_TRUE(failsAt(distance(R"("name": "x,y")"), "joints[0].name", "CSV"));
    const std::string twoJoints = scene(R"("bodies": [{"name": "a", )" + kSphere + R"(}],
           "joints": [{"name": "j", "type": "fixed", "body1": "a"},
                      {"name": "j", "type": "fixed", "body0": "a"}])");
    EXPECT_TRUE(failsAt(twoJoints, "joints[1].name",
                        "duplicate joint name \"j\" (already used at joints[0].name)"));
}

TEST(SceneLoader, JointAndBodyMayShareAName) {
    EXPECT_NO_THROW(parseSceneText(distance(R"("name": "a")"), "t.json"));
}

TEST(SceneLoader, JointFrames) {
    EXPECT_TRUE(failsAt(hinge(R"("anchor0": [0, 0])"), "joints[0].anchor0", "3 numbers"));
    EXPECT_TRUE(
        failsAt(hinge(R"("anchor1": [0, 2e6, 0])"), "joints[0].anchor1[1]", "must be <= 1e+06"));
    EXPECT_TRUE(
        failsAt(hinge(R"("axis0": [0, 0, 0])"), "joints[0].axis0", "must be a non-zero direction"));
    EXPECT_TRUE(failsAt(hinge(R"("axis1": [0, 1e-13, 0])"), "joints[0].axis1", "non-zero"));
    EXPECT_TRUE(
        failsAt(hinge(R"("axis1": [0, "y", 0])"), "joints[0].axis1[1]", "must be a number"));
    EXPECT_TRUE(failsAt(hinge(R"("normal0": [0, 0, 0])"), "joints[0].normal0", "non-zero"));
    // Parallel to the default axis (y), and to a given one.
    EXPECT_TRUE(failsAt(hinge(R"("normal0": [0, -2, 0])"), "joints[0].normal0",
                        "parallel to the joint axis"));
    EXPECT_TRUE(failsAt(hinge(R"("axis1": [1, 0, 0], "normal1": [3, 0, 0])"), "joints[0].normal1",
                        "parallel"));
    EXPECT_TRUE(failsAt(prismatic(R"("axis0": [1, 0, 0], "normal0": [1, 1e-9, 0])"),
                        "joints[0].normal0", "parallel"));
    EXPECT_TRUE(failsAt(withJoint(R"("type": "fixed", "body1": "b", "normal1": [0, 1, 0])"),
                        "joints[0].normal1", "parallel"));
    EXPECT_TRUE(failsAt(spherical(R"("axis0": [0, 0, 1], "normal0": [0, 0, 1])"),
                        "joints[0].normal0", "parallel"));
}

TEST(SceneLoader, NormalsAreMadePerpendicularToTheirAxis) {
    const auto s = parseSceneText(hinge(R"("axis1": [0, 2, 0], "normal1": [1, 1, 0])"), "t.json");
    const JointDef& def = s.joints[0].def;
    EXPECT_EQ(def.axis1, Vec3::UnitY());
    EXPECT_TRUE(def.normal1->isApprox(Vec3::UnitX(), 1e-15));
    EXPECT_FALSE(def.normal0.has_value());
}

TEST(SceneLoader, JointCompliancesAndDamping) {
    EXPECT_TRUE(
        failsAt(distance(R"("compliance": -1)"), "joints[0].compliance", "must be >= 0, got -1"));
    EXPECT_TRUE(
        failsAt(distance(R"("compliance": 1e10)"), "joints[0].compliance", "must be <= 1e+09"));
    EXPECT_TRUE(
        failsAt(distance(R"("compliance": "soft")"), "joints[0].compliance", "must be a number"));
    EXPECT_TRUE(
        failsAt(hinge(R"("limit_compliance": -1)"), "joints[0].limit_compliance", "must be >= 0"));
    EXPECT_TRUE(failsAt(prismatic(R"("limit_compliance": 2e9)"), "joints[0].limit_compliance",
                        "must be <= 1e+09"));
    EXPECT_TRUE(
        failsAt(hinge(R"("drive_compliance": -1)"), "joints[0].drive_compliance", "must be >= 0"));
    EXPECT_TRUE(failsAt(prismatic(R"("drive_compliance": -1)"), "joints[0].drive_compliance",
                        "must be >= 0"));
    EXPECT_TRUE(failsAt(spherical(R"("twist_compliance": -1)"), "joints[0].twist_compliance",
                        "must be >= 0"));
    EXPECT_TRUE(failsAt(spherical(R"("limit_compliance": -1)"), "joints[0].limit_compliance",
                        "must be >= 0"));
    EXPECT_TRUE(failsAt(distance(R"("damping": 1)"), "joints[0].damping", "must be an object"));
    EXPECT_TRUE(failsAt(distance(R"("damping": {"linear": -1})"), "joints[0].damping.linear",
                        "must be >= 0, got -1"));
    EXPECT_TRUE(failsAt(distance(R"("damping": {"angular": 1e7})"), "joints[0].damping.angular",
                        "must be <= 1e+06"));
    EXPECT_TRUE(failsAt(distance(R"("damping": {"rotational": 1})"), "joints[0].damping.rotational",
                        "unknown key"));
    EXPECT_TRUE(
        failsAt(distance(R"("collide": "no")"), "joints[0].collide", "must be true or false"));
}

TEST(SceneLoader, DistanceJoint) {
    EXPECT_TRUE(failsAt(distance(R"("max_distance": -0.5)"), "joints[0].max_distance",
                        "must be >= 0, got -0.5"));
    EXPECT_TRUE(
        failsAt(distance(R"("max_distance": 1e7)"), "joints[0].max_distance", "must be <= 1e+06"));
}

TEST(SceneLoader, HingeJoint) {
    EXPECT_TRUE(failsAt(hinge(R"("limits": [1, -1])"), "joints[0].limits",
                        "lower limit 1 is above upper limit -1"));
    EXPECT_TRUE(failsAt(hinge(R"("limits": [1])"), "joints[0].limits", "[lower, upper]"));
    EXPECT_TRUE(failsAt(hinge(R"("limits": [-1, 0, 1])"), "joints[0].limits", "got an array of 3"));
    EXPECT_TRUE(failsAt(hinge(R"("limits": [-1, 4])"), "joints[0].limits[1]",
                        "must be in [-pi, pi], got 4"));
    EXPECT_TRUE(
        failsAt(hinge(R"("limits": [-3.2, 0])"), "joints[0].limits[0]", "must be in [-pi, pi]"));
    EXPECT_TRUE(failsAt(hinge(R"("target_angle": 4)"), "joints[0].target_angle",
                        "must be in [-pi, pi], got 4"));
    EXPECT_TRUE(failsAt(hinge(R"("target_angle": 0, "target_velocity": 1)"),
                        "joints[0].target_velocity", "not both"));
    EXPECT_TRUE(failsAt(hinge(R"("target_velocity": 1e6)"), "joints[0].target_velocity",
                        "must be <= 1e+05"));
    EXPECT_TRUE(failsAt(hinge(R"("target_velocity": "fast")"), "joints[0].target_velocity",
                        "must be a number"));
}

TEST(SceneLoader, PrismaticJoint) {
    EXPECT_TRUE(failsAt(prismatic(R"("limits": [2, 1])"), "joints[0].limits",
                        "lower limit 2 is above upper limit 1"));
    EXPECT_TRUE(
        failsAt(prismatic(R"("limits": [0, 2e6])"), "joints[0].limits[1]", "must be <= 1e+06"));
    EXPECT_TRUE(failsAt(prismatic(R"("limits": "none")"), "joints[0].limits", "[lower, upper]"));
    EXPECT_TRUE(failsAt(prismatic(R"("target_offset": -2e6)"), "joints[0].target_offset",
                        "must be >= -1e+06"));
    // Prismatic limits are lengths, not angles: beyond pi is fine.
    EXPECT_NO_THROW(
        parseSceneText(prismatic(R"("limits": [-10, 10], "target_offset": 5)"), "t.json"));
}

TEST(SceneLoader, SphericalJoint) {
    EXPECT_TRUE(failsAt(spherical(R"("swing_limit": -0.1)"), "joints[0].swing_limit",
                        "must be in [0, pi], got -0.1"));
    EXPECT_TRUE(failsAt(spherical(R"("swing_limit": 3.5)"), "joints[0].swing_limit",
                        "must be in [0, pi], got 3.5"));
    EXPECT_TRUE(failsAt(spherical(R"("twist_limits": [0.5, -0.5])"), "joints[0].twist_limits",
                        "lower limit 0.5 is above"));
    EXPECT_TRUE(failsAt(spherical(R"("twist_limits": [-4, 0])"), "joints[0].twist_limits[0]",
                        "must be in [-pi, pi]"));
    EXPECT_TRUE(
        failsAt(spherical(R"("twist_limits": 1)"), "joints[0].twist_limits", "[lower, upper]"));
}

TEST(SceneLoader, SphericalTwistComplianceDefaultsToUnset) {
    const auto s = parseSceneText(spherical(R"("limit_compliance": 0.1)"), "t.json");
    EXPECT_FALSE(s.joints[0].def.twistCompliance.has_value());  // the world uses limitCompliance
    EXPECT_FALSE(s.joints[0].def.swingLimit.has_value());
}

}  // namespace
}  // namespace substep
