// Tests engine/scene/scene_loader_bodies.cpp: body keys, names, mass and density, pose,
// velocities and surface properties, and the BodyDef values a valid body maps onto.

#include "scene/scene_loader.h"

#include "scene_loader_test_support.h"

#include <gtest/gtest.h>

#include <string>

namespace substep {
namespace {

using namespace test;

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

TEST(SceneLoader, MassesAndMomentsHaveLowerBounds) {
    // Before: a 1e-110 m sphere at the default density weighed exactly 0 and froze; a mass far
    // below a milligram or a moment below 1e-15 kg m² now fails at the value that causes it.
    EXPECT_TRUE(failsAt(withShape(R"("type": "sphere", "radius": 1e-110)"), "bodies[0].shape.radius",
                        "must be >= 0.0001 (smaller values lose precision or underflow), got 1e-110"));
    EXPECT_TRUE(failsAt(withBody(kSphere + R"(, "mass": 1e-9)"), "bodies[0].mass",
                        "must be >= 1e-06 (smaller values lose precision or underflow), got 1e-09"));
    EXPECT_NO_THROW(parseSceneText(withBody(kSphere + R"(, "mass": 1e-6)"), "t.json"));
    // 1 mm cube of 1e-6 kg/m³: 1e-15 kg.
    EXPECT_TRUE(failsAt(withShape(R"("type": "box", "size": [0.001, 0.001, 0.001])", R"("density": 1e-6)"),
                        "bodies[0].density", "below the 1e-06 kg lower bound"));
    // Defaulted density: the shape is named. A 0.2 mm sphere of water weighs 3.4e-8 kg.
    EXPECT_TRUE(failsAt(withShape(R"("type": "sphere", "radius": 0.0002)"), "bodies[0].shape",
                        "below the 1e-06 kg lower bound"));
    // 1 mg on a 0.1 mm sphere: I = 2/5 m r² = 4e-15 kg m², just above the bound; 1 mg on a
    // 0.1 mm x 0.1 mm x 0.1 mm box: m (a² + b²) / 12 = 1.7e-15; a 1 mg needle (0.1 mm capsule
    // radius, no length): 4e-15. A mass of 1e-6 kg on a smaller moment fails at the mass.
    EXPECT_NO_THROW(parseSceneText(withShape(R"("type": "sphere", "radius": 0.0001)", R"("mass": 1e-6)"), "t.json"));
    EXPECT_NO_THROW(parseSceneText(withShape(R"("type": "box", "size": [0.0001, 0.0001, 0.0001])",
                                             R"("mass": 1e-6)"), "t.json"));
    EXPECT_TRUE(failsAt(withShape(R"("type": "box", "size": [0.0001, 0.0001, 0.0001])", R"("mass": 5e-7)"),
                        "bodies[0].mass", "must be >= 1e-06"));
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

}  // namespace
}  // namespace substep
