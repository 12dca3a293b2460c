// Tests engine/scene/scene.cpp through the ECS: the entities buildScene makes for bodies,
// joints and soft bodies, that the world is created from them in description order, and that a moved
// SceneInstance still steps through its physics system.

#include "ecs/components.h"
#include "ecs/soft_body_component.h"
#include "scene/scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <utility>

namespace substep {
namespace {

SceneDescription pendulumScene() {
    SceneDescription d;
    d.name = "pendulum";
    d.gravity = Vec3(0, -10, 0);
    d.bodies.push_back({"ceiling",
                        {.shape = boxShape(Vec3(1, 0.1, 1)),
                         .type = BodyType::Static,
                         .position = Vec3(0, 2, 0)}});
    d.bodies.push_back({"", {.shape = sphereShape(0.1), .mass = 1, .position = Vec3(5, 0, 0)}});
    d.bodies.push_back(
        {"bob",
         {.shape = sphereShape(0.1), .mass = 2, .position = Vec3(1, 2, 0), .restitution = 0.25}});
    SceneJoint rope{.name = "rope", .body0 = "ceiling", .body1 = "bob", .def = {}};
    rope.def.maxDistance = 1;
    d.joints.push_back(rope);
    d.joints.push_back(
        {.name = "", .body0 = "world", .body1 = "bob", .def = {.type = JointType::Spherical}});
    return d;
}

TEST(SceneEntities, EveryBodyIsAnEntityWithItsComponents) {
    const SceneDescription d = pendulumScene();
    const SceneInstance s = buildScene(d);
    ASSERT_EQ(s.bodyEntities.size(), 3u);
    for (std::size_t i = 0; i < d.bodies.size(); ++i) {
        const ecs::Entity e = s.bodyEntities[i];
        ASSERT_TRUE(s.registry.isValid(e));
        const auto& transform = s.registry.get<ecs::Transform>(e);
        EXPECT_EQ(transform.position, d.bodies[i].def.position);
        const auto& rigidBody = s.registry.get<ecs::RigidBody>(e);
        // Bodies reach the world in description order, after its static anchor (index 0).
        EXPECT_EQ(rigidBody.id.index, i + 1);
        EXPECT_TRUE(s.world().isValid(rigidBody.id));
        EXPECT_EQ(s.registry.get<ecs::Collider>(e).restitution, d.bodies[i].def.restitution);
        EXPECT_TRUE(s.registry.get<ecs::RenderMaterial>(e).visible);
        EXPECT_EQ(s.registry.has<ecs::Name>(e), !d.bodies[i].name.empty());
    }
    EXPECT_EQ(s.registry.get<ecs::Name>(s.bodyEntities[2]).value, "bob");
    ASSERT_EQ(s.namedBodyIds().size(), 2u);
    EXPECT_EQ(s.namedBodyIds()[1].second, s.registry.get<ecs::RigidBody>(s.bodyEntities[2]).id);
    // Static and moving bodies are told apart by colour.
    EXPECT_NE(s.registry.get<ecs::RenderMaterial>(s.bodyEntities[0]).colour,
              s.registry.get<ecs::RenderMaterial>(s.bodyEntities[1]).colour);
}

TEST(SceneEntities, EveryJointIsAnEntityNamingItsBodyEntities) {
    const SceneInstance s = buildScene(pendulumScene());
    ASSERT_EQ(s.jointEntities.size(), 2u);
    const auto& rope = s.registry.get<ecs::Joint>(s.jointEntities[0]);
    EXPECT_EQ(rope.body0, s.bodyEntities[0]);
    EXPECT_EQ(rope.body1, s.bodyEntities[2]);
    EXPECT_EQ(rope.def.maxDistance, 1.0);
    EXPECT_EQ(s.registry.get<ecs::Name>(s.jointEntities[0]).value, "rope");
    ASSERT_EQ(s.namedJointIds().size(), 1u);
    EXPECT_EQ(s.namedJointIds()[0].second, rope.id);

    const auto& pin = s.registry.get<ecs::Joint>(s.jointEntities[1]);
    EXPECT_TRUE(pin.body0.isNull());  // "world"
    EXPECT_TRUE(s.world().isValid(pin.id));
    EXPECT_EQ(pin.id.index, rope.id.index + 1);  // description order
    EXPECT_FALSE(s.registry.has<ecs::Name>(s.jointEntities[1]));
}

TEST(SceneEntities, MovedInstanceStepsThroughItsPhysicsSystem) {
    SceneInstance built = buildScene(pendulumScene());
    SceneInstance s = std::move(built);
    const ecs::Entity free = s.bodyEntities[1];
    for (int i = 0; i < 10; ++i)
        s.physics().step(1.0 / 60.0);
    const BodyId id = s.registry.get<ecs::RigidBody>(free).id;
    EXPECT_EQ(s.registry.get<ecs::Transform>(free).position, s.world().body(id).userPosition());
    EXPECT_LT(s.registry.get<ecs::Transform>(free).position.y(), 0.0);
}

TEST(SceneEntities, DestroyingABodyEntityDropsItsJointsFromTheWorld) {
    SceneInstance s = buildScene(pendulumScene());
    const JointId rope = s.namedJointIds()[0].second;
    const std::vector<std::pair<std::string, BodyId>> bodies = s.namedBodyIds();
    s.physics().destroy(s.bodyEntities[2]);  // bob
    EXPECT_FALSE(s.world().isValid(rope));
    EXPECT_FALSE(s.world().isValid(bodies[1].second));
    EXPECT_TRUE(s.world().isValid(bodies[0].second));
    // A destroyed entity's name goes with it.
    EXPECT_EQ(s.namedBodyIds().size(), bodies.size() - 1);
    EXPECT_EQ(s.world().maxJointError(), 0.0);
}

TEST(SceneEntities, EverySoftBodyIsAnEntityAttachedToItsBodyEntities) {
    SceneDescription d = pendulumScene();
    SceneSoftBody tyre{.name = "tyre",
                       .def = {.type = SoftBodyType::Tyre, .cells = {8, 1, 1}, .position = Vec3(1, 2, 0)},
                       .attachBodies = {"bob"}};
    tyre.def.attachments.push_back({.particles = SoftAttachmentParticles::Inner});
    d.softBodies.push_back(tyre);
    d.softBodies.push_back({.def = {.size = Vec3(0.2, 0.2, 0.2), .position = Vec3(0, 5, 0)},
                            .colour = Vec3(0.1, 0.2, 0.3)});
    const SceneInstance s = buildScene(d);
    ASSERT_EQ(s.softBodyEntities.size(), 2u);
    const ecs::Entity named = s.softBodyNamed("tyre");
    ASSERT_EQ(named, s.softBodyEntities[0]);
    EXPECT_TRUE(s.bodyNamed("tyre").isNull()) << "soft bodies are not bodies";
    const ecs::SoftBody& soft = s.registry.get<ecs::SoftBody>(named);
    ASSERT_EQ(soft.attachedBodies.size(), 1u);
    EXPECT_EQ(soft.attachedBodies[0], s.bodyNamed("bob"));
    EXPECT_TRUE(s.world().isValid(soft.id));
    // The readout is there from the start: 8 x 2 x 2 particles of the tyre's lattice.
    EXPECT_EQ(soft.readout.particles, 32);
    EXPECT_EQ(soft.readout.elements, 8);
    EXPECT_TRUE(s.registry.has<ecs::RenderMaterial>(named));

    const ecs::Entity unnamed = s.softBodyEntities[1];
    EXPECT_EQ(s.registry.tryGet<ecs::Name>(unnamed), nullptr);
    EXPECT_EQ(s.registry.get<ecs::RenderMaterial>(unnamed).colour, Vec3(0.1, 0.2, 0.3));
    // The volume on demand (the write-back after building leaves it NaN).
    EXPECT_TRUE(std::isnan(s.registry.get<ecs::SoftBody>(unnamed).readout.volume));
    EXPECT_NEAR(ecs::softBodyReadout(s.world(), s.registry.get<ecs::SoftBody>(unnamed)).volume, 0.008, 1e-15);

    SceneDescription bad = pendulumScene();
    bad.softBodies.push_back({.def = {.attachments = {{}}}, .attachBodies = {"nobody"}});
    EXPECT_THROW(buildScene(bad), std::invalid_argument);
    SceneDescription mismatched = pendulumScene();
    mismatched.softBodies.push_back({.attachBodies = {"bob"}});
    EXPECT_THROW(buildScene(mismatched), std::invalid_argument);
}

}  // namespace
}  // namespace substep
