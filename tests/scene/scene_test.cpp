// Tests engine/scene/scene.cpp: buildScene creates the world, bodies and joints of a description
// in order, resolves joint body names and records the named ones.

#include "scene/scene.h"
#include "scene/scene_loader.h"

#include <gtest/gtest.h>

#include <stdexcept>

#ifndef SUBSTEP_TEST_DATA_DIR
#define SUBSTEP_TEST_DATA_DIR "tests/data/scenes"
#endif

namespace substep {
namespace {

SceneDescription twoBodies() {
    SceneDescription d;
    d.name = "two";
    d.gravity = Vec3(0, -10, 0);
    d.substeps = 7;
    d.iterations = 3;
    d.bodies.push_back({"ceiling",
                        {.shape = boxShape(Vec3(1, 0.1, 1)),
                         .type = BodyType::Static,
                         .position = Vec3(0, 2, 0)}});
    d.bodies.push_back({"", {.shape = sphereShape(0.1), .mass = 1, .position = Vec3(5, 0, 0)}});
    d.bodies.push_back({"bob", {.shape = sphereShape(0.1), .mass = 2, .position = Vec3(0, 1, 0)}});
    SceneJoint rope{.name = "rope", .body0 = "ceiling", .body1 = "bob", .def = {}};
    rope.def.maxDistance = 1;
    d.joints.push_back(rope);
    d.joints.push_back(
        {.name = "", .body0 = "world", .body1 = "bob", .def = {.type = JointType::Spherical}});
    d.joints.push_back(
        {.name = "pin", .body0 = "", .body1 = "ceiling", .def = {.type = JointType::Fixed}});
    return d;
}

TEST(BuildScene, WorldSettingsComeFromTheDescription) {
    const SceneInstance s = buildScene(twoBodies());
    EXPECT_EQ(s.world().settings().gravity, Vec3(0, -10, 0));
    EXPECT_EQ(s.world().settings().substeps, 7);
    EXPECT_EQ(s.world().settings().iterations, 3);
}

TEST(BuildScene, BodiesInOrderAndNamedOnesRecorded) {
    const SceneInstance s = buildScene(twoBodies());
    ASSERT_EQ(s.namedBodyIds().size(), 2u);
    EXPECT_EQ(s.namedBodyIds()[0].first, "ceiling");
    EXPECT_EQ(s.namedBodyIds()[1].first, "bob");
    const BodyId ceiling = s.namedBodyIds()[0].second;
    const BodyId bob = s.namedBodyIds()[1].second;
    ASSERT_TRUE(s.world().isValid(ceiling));
    ASSERT_TRUE(s.world().isValid(bob));
    EXPECT_LT(ceiling.index, bob.index);
    EXPECT_EQ(s.world().body(ceiling).type, BodyType::Static);
    EXPECT_FALSE(s.world().body(ceiling).isDynamic());
    EXPECT_NEAR(s.world().body(bob).mass, 2.0, 1e-12);
    EXPECT_TRUE(s.world().body(bob).userPosition().isApprox(Vec3(0, 1, 0)));
    // The unnamed body exists too: the world's anchor plus three bodies.
    EXPECT_EQ(s.world().bodies().size(), 4u);
}

TEST(BuildScene, JointBodyNamesResolve) {
    const SceneInstance s = buildScene(twoBodies());
    const BodyId ceiling = s.namedBodyIds()[0].second;
    const BodyId bob = s.namedBodyIds()[1].second;
    ASSERT_EQ(s.namedJointIds().size(), 2u);
    EXPECT_EQ(s.namedJointIds()[0].first, "rope");
    EXPECT_EQ(s.namedJointIds()[1].first, "pin");
    ASSERT_EQ(s.world().joints().size(), 3u);

    const Joint& rope = s.world().joint(s.namedJointIds()[0].second);
    EXPECT_EQ(rope.type(), JointType::Distance);
    EXPECT_EQ(rope.body0, ceiling.index);
    EXPECT_EQ(rope.body1, bob.index);
    EXPECT_EQ(rope.distance().maxDistance, 1.0);

    // "world" and "" both mean the world's anchor body, index 0.
    const Joint& unnamed = s.world().joints()[1];
    EXPECT_EQ(unnamed.type(), JointType::Spherical);
    EXPECT_EQ(unnamed.body0, 0u);
    EXPECT_EQ(unnamed.body1, bob.index);
    const Joint& pin = s.world().joint(s.namedJointIds()[1].second);
    EXPECT_EQ(pin.body0, 0u);
    EXPECT_EQ(pin.body1, ceiling.index);
}

TEST(BuildScene, UnknownBodyNameThrows) {
    SceneDescription d = twoBodies();
    d.joints[0].body1 = "nobody";
    EXPECT_THROW(buildScene(d), std::invalid_argument);
}

TEST(BuildScene, AmbiguousBodyNamesThrow) {
    SceneDescription d = twoBodies();
    d.bodies[1].name = "bob";
    EXPECT_THROW(buildScene(d), std::invalid_argument);
    d.bodies[1].name = "world";
    EXPECT_THROW(buildScene(d), std::invalid_argument);
}

TEST(BuildScene, BuildsTheFullSceneFile) {
    const SceneInstance s =
        buildScene(loadSceneFile(std::string(SUBSTEP_TEST_DATA_DIR) + "/full.json"));
    EXPECT_EQ(s.namedBodyIds().size(), 6u);
    EXPECT_EQ(s.namedJointIds().size(), 5u);
    EXPECT_EQ(s.world().bodies().size(), 8u);
    EXPECT_EQ(s.world().joints().size(), 6u);
    EXPECT_EQ(s.world().settings().substeps, 40);
    EXPECT_TRUE(s.world().isFinite());
}

}  // namespace
}  // namespace substep
