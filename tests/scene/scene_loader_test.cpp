// Tests engine/scene/scene_loader.cpp: every validation rule names the file and the exact JSON
// path of the offending value, and a valid file maps onto the right BodyDef/JointDef values.

#include "scene/scene_loader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#ifndef SUBSTEP_TEST_DATA_DIR
#define SUBSTEP_TEST_DATA_DIR "tests/data/scenes"
#endif

namespace substep {
namespace {

const std::string kDataDir = SUBSTEP_TEST_DATA_DIR;

/// Passes when parsing `text` throws a SceneError whose one-line message is
/// `t.json: PATH: ...` and contains `fragment`.
::testing::AssertionResult failsAt(const std::string& text, const std::string& path,
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

std::string scene(const std::string& members) {
    return R"({"substep_scene": 1)" + (members.empty() ? "" : ", " + members) + "}";
}
/// A scene with one body made of `members` (add a shape yourself if you need one).
std::string withBody(const std::string& members) {
    return scene(R"("bodies": [{)" + members + "}]");
}
const std::string kSphere = R"("shape": {"type": "sphere", "radius": 0.5})";
std::string withShape(const std::string& shapeMembers, const std::string& more = "") {
    return withBody(R"("shape": {)" + shapeMembers + "}" + (more.empty() ? "" : ", " + more));
}
/// A scene with bodies "a" (static) and "b" and one joint made of `members`.
std::string withJoint(const std::string& members) {
    return scene(
        R"("bodies": [{"name": "a", "static": true, "shape": {"type": "box", "size": [1, 1, 1]}},
                               {"name": "b", "shape": {"type": "sphere", "radius": 0.5}}],
                    "joints": [{)" +
        members + "}]");
}
std::string hinge(const std::string& more) {
    return withJoint(R"("type": "hinge", "body0": "a", "body1": "b", )" + more);
}
std::string prismatic(const std::string& more) {
    return withJoint(R"("type": "prismatic", "body0": "a", "body1": "b", )" + more);
}
std::string spherical(const std::string& more) {
    return withJoint(R"("type": "spherical", "body0": "a", "body1": "b", )" + more);
}
std::string distance(const std::string& more) {
    return withJoint(R"("type": "distance", "body0": "a", "body1": "b", )" + more);
}

// ---- Valid input ---------------------------------------------------------------------------

TEST(SceneLoader, MinimalSceneTakesTheDefaults) {
    const SceneDescription s = parseSceneText(scene(""), "scenes/minimal.json");
    EXPECT_EQ(s.name, "minimal");
    EXPECT_EQ(s.gravity, Vec3(0, -9.81, 0));
    EXPECT_DOUBLE_EQ(s.dt, 1.0 / 60.0);
    EXPECT_EQ(s.substeps, 20);
    EXPECT_EQ(s.iterations, 1);
    EXPECT_TRUE(s.bodies.empty());
    EXPECT_TRUE(s.joints.empty());
    EXPECT_FALSE(s.camera.has_value());
}

TEST(SceneLoader, BodyDefaults) {
    const SceneDescription s = parseSceneText(withBody(kSphere), "t.json");
    ASSERT_EQ(s.bodies.size(), 1u);
    const SceneBody& b = s.bodies[0];
    EXPECT_TRUE(b.name.empty());
    EXPECT_EQ(b.def.type, BodyType::Dynamic);
    EXPECT_EQ(b.def.shape.type, ShapeType::Sphere);
    EXPECT_EQ(b.def.shape.radius, 0.5);
    EXPECT_EQ(b.def.mass, 0.0);
    EXPECT_EQ(b.def.density, 1000.0);
    EXPECT_EQ(b.def.position, Vec3::Zero());
    EXPECT_TRUE(b.def.orientation.coeffs().isApprox(Quat::Identity().coeffs()));
    EXPECT_EQ(b.def.staticFriction, 0.5);
    EXPECT_EQ(b.def.dynamicFriction, 0.3);
    EXPECT_EQ(b.def.restitution, 0.0);
    EXPECT_TRUE(b.def.collide);
}

TEST(SceneLoader, FullSceneRoundTrips) {
    const SceneDescription s = loadSceneFile(kDataDir + "/full.json");
    EXPECT_EQ(s.name, "full");  // the file stem, not the "name" key
    EXPECT_EQ(s.gravity, Vec3(0, -10, 0.5));
    EXPECT_EQ(s.dt, 0.01);
    EXPECT_EQ(s.substeps, 40);
    EXPECT_EQ(s.iterations, 2);
    ASSERT_TRUE(s.camera.has_value());
    EXPECT_EQ(s.camera->position, Vec3(1, 2, 3));
    EXPECT_EQ(s.camera->target, Vec3(0, 1, 0));
    EXPECT_EQ(s.camera->fov, 0.9);

    ASSERT_EQ(s.bodies.size(), 7u);
    const BodyDef& ground = s.bodies[0].def;
    EXPECT_EQ(s.bodies[0].name, "ground");
    EXPECT_EQ(ground.type, BodyType::Static);
    EXPECT_EQ(ground.shape.type, ShapeType::Plane);
    EXPECT_EQ(ground.shape.normal, Vec3(0, 1, 0));  // normalised
    EXPECT_EQ(ground.shape.offset, -1.0);
    EXPECT_EQ(ground.staticFriction, 0.8);
    EXPECT_EQ(ground.dynamicFriction, 0.6);
    EXPECT_EQ(ground.restitution, 0.25);

    const BodyDef& ceiling = s.bodies[1].def;
    EXPECT_EQ(ceiling.type, BodyType::Static);
    EXPECT_EQ(ceiling.shape.type, ShapeType::Box);
    EXPECT_EQ(ceiling.shape.size, Vec3(1, 0.1, 1));
    EXPECT_EQ(ceiling.position, Vec3(0, 2, 0));
    EXPECT_FALSE(ceiling.collide);

    const BodyDef& box = s.bodies[2].def;
    EXPECT_EQ(s.bodies[2].name, "box");
    EXPECT_EQ(box.type, BodyType::Dynamic);
    EXPECT_EQ(box.shape.size, Vec3(0.2, 0.3, 0.4));
    EXPECT_EQ(box.mass, 2.5);
    EXPECT_EQ(box.position, Vec3(0, 1.5, 0));
    EXPECT_EQ(box.orientation.coeffs(), Quat::Identity().coeffs());  // [2,0,0,0] normalised
    EXPECT_EQ(box.velocity, Vec3(1, 2, 3));
    EXPECT_EQ(box.angularVelocity, Vec3(-1, 0, 4));
    EXPECT_EQ(box.staticFriction, 0.5);
    EXPECT_EQ(box.dynamicFriction, 0.3);
    EXPECT_EQ(box.restitution, 0.5);

    const BodyDef& ball = s.bodies[3].def;
    EXPECT_EQ(ball.shape.type, ShapeType::Sphere);
    EXPECT_EQ(ball.shape.radius, 0.1);
    EXPECT_EQ(ball.mass, 0.0);
    EXPECT_EQ(ball.density, 7800.0);

    const SceneBody& capsule = s.bodies[4];
    EXPECT_TRUE(capsule.name.empty());
    EXPECT_EQ(capsule.def.shape.type, ShapeType::Capsule);
    EXPECT_EQ(capsule.def.shape.radius, 0.05);
    EXPECT_EQ(capsule.def.shape.length, 0.4);
    EXPECT_NEAR(
        capsule.def.orientation.angularDistance(Quat(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitZ()))),
        0.0, 1e-12);

    ASSERT_EQ(s.joints.size(), 6u);
    const SceneJoint& spring = s.joints[0];
    EXPECT_EQ(spring.name, "spring");
    EXPECT_EQ(spring.body0, "ceiling");
    EXPECT_EQ(spring.body1, "box");
    EXPECT_EQ(spring.def.type, JointType::Distance);
    EXPECT_EQ(spring.def.anchor0, Vec3(0, -0.05, 0));
    EXPECT_EQ(spring.def.anchor1, Vec3(0, 0.15, 0));
    EXPECT_EQ(spring.def.maxDistance, 0.5);
    EXPECT_EQ(spring.def.compliance, 0.01);
    EXPECT_EQ(spring.def.linearDamping, 0.1);
    EXPECT_EQ(spring.def.angularDamping, 0.2);
    EXPECT_TRUE(spring.def.collide);
    EXPECT_TRUE(spring.def.body0.isNull());  // ids are buildScene's job

    const SceneJoint& fixed = s.joints[1];
    EXPECT_TRUE(fixed.name.empty());
    EXPECT_EQ(fixed.def.type, JointType::Fixed);
    EXPECT_EQ(fixed.body0, "world");
    EXPECT_EQ(fixed.body1, "ball");
    EXPECT_EQ(fixed.def.anchor0, Vec3(1, 1.1, 0));
    EXPECT_FALSE(fixed.def.collide);
    EXPECT_EQ(fixed.def.axis0, Vec3::UnitY());
    EXPECT_FALSE(fixed.def.normal0.has_value());

    const SceneJoint& door = s.joints[2];
    EXPECT_EQ(door.def.type, JointType::Hinge);
    EXPECT_TRUE(door.body0.empty());
    EXPECT_EQ(door.def.axis0, Vec3(0, 0, 1));  // normalised
    EXPECT_EQ(door.def.axis1, Vec3(0, 0, 1));
    ASSERT_TRUE(door.def.normal0.has_value());
    EXPECT_TRUE(door.def.normal0->isApprox(Vec3(1, 0, 0)));  // made perpendicular to the axis
    EXPECT_EQ(*door.def.normal1, Vec3(1, 0, 0));
    ASSERT_TRUE(door.def.limits.has_value());
    EXPECT_EQ(door.def.limits->lower, -1.0);
    EXPECT_EQ(door.def.limits->upper, 1.5);
    EXPECT_EQ(door.def.limitCompliance, 0.001);
    EXPECT_EQ(door.def.targetAngle, 0.25);
    EXPECT_FALSE(door.def.targetVelocity.has_value());
    EXPECT_EQ(door.def.driveCompliance, 0.002);

    const SceneJoint& motor = s.joints[3];
    EXPECT_EQ(motor.def.targetVelocity, 3.5);
    EXPECT_FALSE(motor.def.targetAngle.has_value());
    // 3.1416 is pi rounded: accepted and clamped.
    EXPECT_EQ(motor.def.limits->lower, -M_PI);
    EXPECT_EQ(motor.def.limits->upper, M_PI);

    const SceneJoint& rail = s.joints[4];
    EXPECT_EQ(rail.def.type, JointType::Prismatic);
    EXPECT_EQ(rail.def.axis0, Vec3(1, 0, 0));
    EXPECT_EQ(rail.def.limits->lower, -0.5);
    EXPECT_EQ(rail.def.limits->upper, 2.0);
    EXPECT_EQ(rail.def.limitCompliance, 0.0001);
    EXPECT_EQ(rail.def.targetOffset, 0.75);
    EXPECT_EQ(rail.def.driveCompliance, 0.003);

    const SceneJoint& shoulder = s.joints[5];
    EXPECT_EQ(shoulder.def.type, JointType::Spherical);
    EXPECT_EQ(shoulder.def.swingLimit, 0.8);
    ASSERT_TRUE(shoulder.def.twistLimits.has_value());
    EXPECT_EQ(shoulder.def.twistLimits->lower, -0.3);
    EXPECT_EQ(shoulder.def.twistLimits->upper, 0.4);
    EXPECT_EQ(shoulder.def.limitCompliance, 0.004);
    EXPECT_EQ(shoulder.def.twistCompliance, 0.005);
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

TEST(SceneLoader, NormalsAreMadePerpendicularToTheirAxis) {
    const auto s = parseSceneText(hinge(R"("axis1": [0, 2, 0], "normal1": [1, 1, 0])"), "t.json");
    const JointDef& def = s.joints[0].def;
    EXPECT_EQ(def.axis1, Vec3::UnitY());
    EXPECT_TRUE(def.normal1->isApprox(Vec3::UnitX(), 1e-15));
    EXPECT_FALSE(def.normal0.has_value());
}

TEST(SceneLoader, SphericalTwistComplianceDefaultsToUnset) {
    const auto s = parseSceneText(spherical(R"("limit_compliance": 0.1)"), "t.json");
    EXPECT_FALSE(s.joints[0].def.twistCompliance.has_value());  // the world uses limitCompliance
    EXPECT_FALSE(s.joints[0].def.swingLimit.has_value());
}

TEST(SceneLoader, WholeFloatsCountAsIntegers) {
    const auto s = parseSceneText(scene(R"("substeps": 20.0, "iterations": 1e1)"), "t.json");
    EXPECT_EQ(s.substeps, 20);
    EXPECT_EQ(s.iterations, 10);
}

TEST(SceneLoader, AngleBoundsAcceptExactPi) {
    EXPECT_NO_THROW(
        parseSceneText(hinge(R"("limits": [-3.141592653589793, 3.141592653589793])"), "t.json"));
    EXPECT_NO_THROW(
        parseSceneText(spherical(R"("swing_limit": 0, "twist_limits": [0, 0])"), "t.json"));
    EXPECT_NO_THROW(parseSceneText(hinge(R"("limits": [0.5, 0.5])"), "t.json"));  // lo == hi locks
}

TEST(SceneLoader, StaticBodiesMayHaveZeroVelocityAndPlanesIdentityPose) {
    EXPECT_NO_THROW(parseSceneText(
        withBody(kSphere +
                 R"(, "static": true, "velocity": [0, 0, 0], "angular_velocity": [0, 0, 0])"),
        "t.json"));
    EXPECT_NO_THROW(parseSceneText(
        withShape(R"("type": "plane")",
                  R"("static": true, "position": [0, 0, 0], "orientation": [1, 0, 0, 0])"),
        "t.json"));
}

TEST(SceneLoader, CapsuleOfZeroLengthIsASphere) {
    EXPECT_NO_THROW(
        parseSceneText(withShape(R"("type": "capsule", "radius": 1, "length": 0)"), "t.json"));
}

TEST(SceneLoader, JointsMayReferenceTheWorldOnEitherSide) {
    const auto s =
        parseSceneText(withJoint(R"("type": "fixed", "body0": "b", "body1": "world")"), "t.json");
    EXPECT_EQ(s.joints[0].body0, "b");
    EXPECT_EQ(s.joints[0].body1, "world");
    const auto t = parseSceneText(withJoint(R"("type": "fixed", "body0": "b")"), "t.json");
    EXPECT_TRUE(t.joints[0].body1.empty());
}

TEST(SceneLoader, JointAndBodyMayShareAName) {
    EXPECT_NO_THROW(parseSceneText(distance(R"("name": "a")"), "t.json"));
}

// ---- Files and syntax ----------------------------------------------------------------------

TEST(SceneLoader, UnreadableFileNamesTheFile) {
    try {
        loadSceneFile("/nonexistent/dir/missing.json");
        FAIL() << "no error";
    } catch (const SceneError& e) {
        EXPECT_EQ(std::string(e.what()),
                  "/nonexistent/dir/missing.json: cannot read: No such file or directory");
        EXPECT_EQ(e.file(), "/nonexistent/dir/missing.json");
        EXPECT_TRUE(e.path().empty());
    }
    try {
        loadSceneFile(kDataDir);
        FAIL() << "no error";
    } catch (const SceneError& e) {
        EXPECT_EQ(std::string(e.what()).rfind(kDataDir + ": cannot read: ", 0), 0u) << e.what();
    }
}

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

// ---- Top level -----------------------------------------------------------------------------

TEST(SceneLoader, TopLevel) {
    EXPECT_TRUE(failsAt("[1, 2]", "top level", "must be a JSON object, got an array"));
    EXPECT_TRUE(failsAt("{}", "substep_scene", "missing"));
    EXPECT_TRUE(failsAt(R"({"substep_scene": 2})", "substep_scene", "unsupported version 2"));
    EXPECT_TRUE(failsAt(R"({"substep_scene": "1"})", "substep_scene", "must be 1"));
    EXPECT_TRUE(failsAt(R"({"substep_scene": 1.5})", "substep_scene", "unsupported version 1.5"));
    // The version is checked before anything else.
    EXPECT_TRUE(
        failsAt(R"({"bogus": 1, "substep_scene": 3})", "substep_scene", "unsupported version 3"));
    EXPECT_TRUE(failsAt(scene(R"("gravty": [0, -10, 0])"), "gravty",
                        "unknown key (did you mean \"gravity\"?)"));
    EXPECT_TRUE(failsAt(scene(R"("zzz": 1)"), "zzz", "unknown key (expected substep_scene"));
    EXPECT_TRUE(failsAt(scene(R"("odd key": 1)"), R"(["odd key"])", "unknown key"));
    EXPECT_TRUE(failsAt(scene(R"("name": 3)"), "name", "must be a string, got 3"));
    EXPECT_TRUE(
        failsAt(scene(R"("description": ["x"])"), "description", "must be a string, got an array"));
}

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

TEST(SceneLoader, ArraysOfBodiesAndJoints) {
    EXPECT_TRUE(
        failsAt(scene(R"("bodies": {})"), "bodies", "must be an array of bodies, got an object"));
    EXPECT_TRUE(failsAt(scene(R"("bodies": [3])"), "bodies[0]", "must be a body object, got 3"));
    EXPECT_TRUE(failsAt(scene(R"("joints": 1)"), "joints", "must be an array of joints"));
    EXPECT_TRUE(
        failsAt(scene(R"("joints": [[]])"), "joints[0]", "must be a joint object, got an array"));
}

// ---- Bodies --------------------------------------------------------------------------------

TEST(SceneLoader, BodyKeysAndNames) {
    EXPECT_TRUE(failsAt(withBody(kSphere + R"(, "colide": false)"), "bodies[0].colide",
                        "did you mean \"collide\""));
    EXPECT_TRUE(failsAt(withBody(kSphere + R"(, "kinematic": true)"), "bodies[0].kinematic",
                        "unknown key"));
    EXPECT_TRUE(
        failsAt(withBody(kSphere + R"(, "name": 7)"), "bodies[0].name", "must be a string"));
    EXPECT_TRUE(
        failsAt(withBody(kSphere + R"(, "name": "")"), "bodies[0].name", "must not be empty"));
    EXPECT_TRUE(failsAt(withBody(kSphere + R"(, "name": "world")"), "bodies[0].name", "reserved"));
    EXPECT_TRUE(failsAt(withBody(kSphere + R"(, "name": "a,b")"), "bodies[0].name", "CSV"));
    EXPECT_TRUE(failsAt(withBody(kSphere + R"(, "name": "a\"b")"), "bodies[0].name", "CSV"));
    EXPECT_TRUE(
        failsAt(withBody(kSphere + R"(, "name": "a\tb")"), "bodies[0].name", "control characters"));
    EXPECT_TRUE(failsAt(scene(R"("bodies": [{"name": "x", )" + kSphere + R"(}, {)" + kSphere +
                              R"(}, {"name": "x", )" + kSphere + "}]"),
                        "bodies[2].name",
                        "duplicate body name \"x\" (already used at bodies[0].name)"));
    EXPECT_TRUE(failsAt(withBody(kSphere + R"(, "static": "yes")"), "bodies[0].static",
                        "must be true or false"));
    EXPECT_TRUE(failsAt(withBody(kSphere + R"(, "collide": 1)"), "bodies[0].collide",
                        "must be true or false, got 1"));
}

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

TEST(SceneLoader, MassAndDensity) {
    EXPECT_TRUE(
        failsAt(withBody(kSphere + R"(, "mass": 0)"), "bodies[0].mass", "must be > 0, got 0"));
    EXPECT_TRUE(
        failsAt(withBody(kSphere + R"(, "mass": -1)"), "bodies[0].mass", "must be > 0, got -1"));
    EXPECT_TRUE(
        failsAt(withBody(kSphere + R"(, "mass": 1e10)"), "bodies[0].mass", "must be <= 1e+09"));
    EXPECT_TRUE(
        failsAt(withBody(kSphere + R"(, "mass": [1])"), "bodies[0].mass", "must be a number"));
    EXPECT_TRUE(
        failsAt(withBody(kSphere + R"(, "density": 0)"), "bodies[0].density", "must be > 0"));
    EXPECT_TRUE(failsAt(withBody(kSphere + R"(, "density": 1e7)"), "bodies[0].density",
                        "must be <= 1e+06"));
    EXPECT_TRUE(failsAt(withBody(kSphere + R"(, "mass": 1, "density": 1000)"), "bodies[0].density",
                        "not both"));
    EXPECT_TRUE(failsAt(withBody(kSphere + R"(, "static": true, "mass": 1)"), "bodies[0].mass",
                        "static body has no mass"));
    EXPECT_TRUE(failsAt(withBody(kSphere + R"(, "static": true, "density": 1)"),
                        "bodies[0].density", "static body has no density"));
    // The mass a density gives is bounded too: at the density, or at the shape if defaulted.
    EXPECT_TRUE(failsAt(withShape(R"("type": "box", "size": [1000, 1000, 1000])"),
                        "bodies[0].shape", "above the 1e+09 kg"));
    EXPECT_TRUE(
        failsAt(withShape(R"("type": "box", "size": [100, 100, 100])", R"("density": 2000)"),
                "bodies[0].density", "above the 1e+09 kg"));
    // A static body of that size is fine: it has no mass.
    EXPECT_NO_THROW(parseSceneText(
        withShape(R"("type": "box", "size": [1000, 1, 1000])", R"("static": true)"), "t.json"));
}

TEST(SceneLoader, PoseAndVelocities) {
    EXPECT_TRUE(
        failsAt(withBody(kSphere + R"(, "position": [0, 1])"), "bodies[0].position", "3 numbers"));
    EXPECT_TRUE(failsAt(withBody(kSphere + R"(, "position": {"x": 0})"), "bodies[0].position",
                        "got an object"));
    EXPECT_TRUE(failsAt(withBody(kSphere + R"(, "position": [0, 1, "x"])"), "bodies[0].position[2]",
                        "must be a number"));
    EXPECT_TRUE(failsAt(withBody(kSphere + R"(, "position": [0, 2e6, 0])"), "bodies[0].position[1]",
                        "must be <= 1e+06"));
    EXPECT_TRUE(failsAt(withBody(kSphere + R"(, "position": [-2e6, 0, 0])"),
                        "bodies[0].position[0]", "must be >= -1e+06"));
    EXPECT_TRUE(failsAt(withBody(kSphere + R"(, "orientation": [0, 0, 0, 0])"),
                        "bodies[0].orientation", "non-zero quaternion"));
    EXPECT_TRUE(failsAt(withBody(kSphere + R"(, "orientation": [1, 0, 0])"),
                        "bodies[0].orientation", "[w, x, y, z]"));
    EXPECT_TRUE(failsAt(withBody(kSphere + R"(, "orientation": [1, 0, 0, "0"])"),
                        "bodies[0].orientation[3]", "must be a number"));
    EXPECT_TRUE(failsAt(withBody(kSphere + R"(, "velocity": [0, 0, 2e5])"), "bodies[0].velocity[2]",
                        "must be <= 1e+05"));
    EXPECT_TRUE(
        failsAt(withBody(kSphere + R"(, "velocity": 1)"), "bodies[0].velocity", "3 numbers"));
    EXPECT_TRUE(failsAt(withBody(kSphere + R"(, "angular_velocity": [-2e5, 0, 0])"),
                        "bodies[0].angular_velocity[0]", "must be >= -1e+05"));
    EXPECT_TRUE(failsAt(withBody(kSphere + R"(, "static": true, "velocity": [1, 0, 0])"),
                        "bodies[0].velocity", "static body does not move"));
    EXPECT_TRUE(failsAt(withBody(kSphere + R"(, "static": true, "angular_velocity": [0, 1, 0])"),
                        "bodies[0].angular_velocity", "static body does not move"));
}

TEST(SceneLoader, SurfaceProperties) {
    EXPECT_TRUE(failsAt(withBody(kSphere + R"(, "friction": 0.5)"), "bodies[0].friction",
                        "must be an object"));
    EXPECT_TRUE(failsAt(withBody(kSphere + R"(, "friction": {"kinetic": 0.5})"),
                        "bodies[0].friction.kinetic", "unknown key"));
    EXPECT_TRUE(failsAt(withBody(kSphere + R"(, "friction": {"static": -0.1})"),
                        "bodies[0].friction.static", "must be >= 0, got -0.1"));
    EXPECT_TRUE(failsAt(withBody(kSphere + R"(, "friction": {"dynamic": -1})"),
                        "bodies[0].friction.dynamic", "must be >= 0"));
    EXPECT_TRUE(failsAt(withBody(kSphere + R"(, "friction": {"dynamic": 1e4})"),
                        "bodies[0].friction.dynamic", "must be <= 1000"));
    EXPECT_TRUE(failsAt(withBody(kSphere + R"(, "restitution": 1.5)"), "bodies[0].restitution",
                        "must be in [0, 1], got 1.5"));
    EXPECT_TRUE(failsAt(withBody(kSphere + R"(, "restitution": -0.1)"), "bodies[0].restitution",
                        "must be in [0, 1], got -0.1"));
    // Either friction coefficient alone keeps the other's default.
    const auto s = parseSceneText(withBody(kSphere + R"(, "friction": {"static": 0.9})"), "t.json");
    EXPECT_EQ(s.bodies[0].def.staticFriction, 0.9);
    EXPECT_EQ(s.bodies[0].def.dynamicFriction, 0.3);
}

// ---- Joints --------------------------------------------------------------------------------

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

// ---- Camera --------------------------------------------------------------------------------

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

// ---- The error type ------------------------------------------------------------------------

TEST(SceneLoader, ErrorCarriesItsParts) {
    try {
        parseSceneText(withBody(R"("shape": {"type": "sphere", "radius": -1})"), "scenes/a.json");
        FAIL();
    } catch (const std::runtime_error& e) {
        EXPECT_EQ(std::string(e.what()),
                  "scenes/a.json: bodies[0].shape.radius: must be > 0, got -1");
        const auto* scene = dynamic_cast<const SceneError*>(&e);
        ASSERT_NE(scene, nullptr);
        EXPECT_EQ(scene->file(), "scenes/a.json");
        EXPECT_EQ(scene->path(), "bodies[0].shape.radius");
        EXPECT_EQ(scene->problem(), "must be > 0, got -1");
    }
}

TEST(SceneLoader, LoadsAFileWrittenAtRunTime) {
    const auto path =
        std::filesystem::temp_directory_path() / "substep_scene_loader_test_scene.json";
    {
        std::ofstream out(path);
        out << "\xEF\xBB\xBF" << scene(R"("substeps": 7)");  // a UTF-8 byte order mark is tolerated
    }
    const SceneDescription s = loadSceneFile(path.string());
    EXPECT_EQ(s.name, "substep_scene_loader_test_scene");
    EXPECT_EQ(s.substeps, 7);
    std::filesystem::remove(path);
}

}  // namespace
}  // namespace substep
