// Tests engine/ecs/physics_system.cpp: bodies and joints created from components (joints only
// once both bodies exist), Transform following the world (free fall against its closed form),
// and destroying entities taking their world bodies and joints with them.

#include "ecs/physics_system.h"
#include "ecs/body_components.h"
#include "ecs/components.h"
#include "ecs/registry.h"
#include "physics/world.h"

#include <gtest/gtest.h>

#include <cmath>

namespace substep::ecs {
namespace {

constexpr double kG = 10.0;
constexpr double kDt = 1.0 / 60.0;
constexpr int kSubsteps = 20;

World freeFallWorld() {
    return World(WorldSettings{.gravity = Vec3(0, -kG, 0), .substeps = kSubsteps, .iterations = 1});
}

Entity addBody(Registry& registry, const BodyDef& def) {
    const Entity e = registry.create();
    emplaceBody(registry, e, def);
    return e;
}

/// Live bodies in the world besides its static anchor (index 0).
int liveBodies(const World& world) {
    int count = 0;
    for (std::size_t i = 1; i < world.bodies().size(); ++i)
        count += world.bodies()[i].alive;
    return count;
}

int liveJoints(const World& world) {
    int count = 0;
    for (const substep::Joint& joint : world.joints())
        count += joint.alive;
    return count;
}

TEST(PhysicsSystem, SyncCreatesBodiesInComponentOrderOnce) {
    Registry registry;
    World world = freeFallWorld();
    PhysicsSystem physics(registry, world);
    const Entity a = addBody(registry, {.shape = sphereShape(0.1), .position = Vec3(0, 1, 0)});
    const Entity b =
        addBody(registry, {.shape = boxShape(Vec3(1, 1, 1)), .position = Vec3(2, 0, 0)});
    physics.sync();
    const BodyId idA = registry.get<RigidBody>(a).id;
    const BodyId idB = registry.get<RigidBody>(b).id;
    ASSERT_TRUE(world.isValid(idA));
    ASSERT_TRUE(world.isValid(idB));
    EXPECT_LT(idA.index, idB.index);
    EXPECT_EQ(world.body(idB).userPosition(), Vec3(2, 0, 0));

    physics.sync();  // nothing new to create
    EXPECT_EQ(liveBodies(world), 2);
    EXPECT_EQ(registry.get<RigidBody>(a).id, idA);
}

TEST(PhysicsSystem, BodyWaitsForItsTransform) {
    Registry registry;
    World world = freeFallWorld();
    PhysicsSystem physics(registry, world);
    const Entity e = registry.create();
    registry.emplace<RigidBody>(e, RigidBody{.mass = 1.0});
    physics.sync();
    EXPECT_TRUE(registry.get<RigidBody>(e).id.isNull());
    registry.emplace<Transform>(e, Transform{.position = Vec3(0, 3, 0)});
    physics.sync();
    ASSERT_FALSE(registry.get<RigidBody>(e).id.isNull());
    EXPECT_EQ(world.body(registry.get<RigidBody>(e).id).userPosition(), Vec3(0, 3, 0));
}

TEST(PhysicsSystem, FallingBodysTransformFollowsTheClosedForm) {
    Registry registry;
    World world = freeFallWorld();
    PhysicsSystem physics(registry, world);
    const double y0 = 5.0;
    // A rotated box: the Transform must be the user frame, not the principal frame.
    const Quat tilt(Eigen::AngleAxisd(0.3, Vec3(1, 2, 3).normalized()));
    const Entity box = addBody(registry, {.shape = boxShape(Vec3(0.2, 0.4, 0.6)),
                                          .mass = 1.0,
                                          .position = Vec3(1, y0, -2),
                                          .orientation = tilt});
    const Entity ground = addBody(registry, {.shape = boxShape(Vec3(1, 0.1, 1)),
                                             .type = BodyType::Static,
                                             .position = Vec3(0, -100, 0)});

    const int frames = 60;
    for (int i = 0; i < frames; ++i)
        physics.step(kDt);

    // Symplectic Euler over n substeps of h gives y0 − g h² n(n+1)/2 exactly; it trails the
    // closed form y0 − g t²/2 by g h t / 2.
    const double t = frames * kDt;
    const double h = kDt / kSubsteps;
    const int n = frames * kSubsteps;
    const Transform& transform = registry.get<Transform>(box);
    EXPECT_NEAR(transform.position.y(), y0 - kG * h * h * n * (n + 1) / 2.0, 1e-9);
    EXPECT_NEAR(transform.position.y(), y0 - kG * t * t / 2.0, kG * h * t / 2.0 + 1e-9);
    EXPECT_NEAR(transform.position.x(), 1.0, 1e-12);
    EXPECT_NEAR(transform.position.z(), -2.0, 1e-12);
    EXPECT_LT(transform.rotation.angularDistance(tilt), 1e-12);
    const Body& body = world.body(registry.get<RigidBody>(box).id);
    EXPECT_EQ(transform.position, body.userPosition());

    // The static body's Transform is left exactly as given.
    EXPECT_EQ(registry.get<Transform>(ground).position, Vec3(0, -100, 0));
}

TEST(PhysicsSystem, JointWaitsUntilBothBodiesExist) {
    Registry registry;
    World world = freeFallWorld();
    PhysicsSystem physics(registry, world);
    const Entity upper = addBody(registry, {.shape = sphereShape(0.1), .type = BodyType::Static});
    const Entity lower = registry.create();
    const Entity joint = registry.create();
    registry.emplace<Joint>(joint, Joint{.def = {.type = JointType::Spherical,
                                                 .anchor0 = Vec3(0, -0.5, 0),
                                                 .anchor1 = Vec3(0, 0.5, 0)},
                                         .body0 = upper,
                                         .body1 = lower});
    physics.sync();
    EXPECT_TRUE(registry.get<Joint>(joint).id.isNull());  // lower has no body yet
    EXPECT_EQ(liveJoints(world), 0);

    emplaceBody(registry, lower, {.shape = sphereShape(0.1), .position = Vec3(0, -1, 0)});
    physics.sync();
    const JointId id = registry.get<Joint>(joint).id;
    ASSERT_TRUE(world.isValid(id));
    EXPECT_EQ(world.joint(id).body0, registry.get<RigidBody>(upper).id.index);
    EXPECT_EQ(world.joint(id).body1, registry.get<RigidBody>(lower).id.index);
}

TEST(PhysicsSystem, NullJointSideIsTheWorld) {
    Registry registry;
    World world = freeFallWorld();
    PhysicsSystem physics(registry, world);
    const Entity bob = addBody(registry, {.shape = sphereShape(0.1), .position = Vec3(0, -1, 0)});
    const Entity joint = registry.create();
    registry.emplace<Joint>(joint, Joint{.def = {.type = JointType::Distance, .maxDistance = 1.0},
                                         .body0 = kNullEntity,
                                         .body1 = bob});
    physics.sync();
    const JointId id = registry.get<Joint>(joint).id;
    ASSERT_TRUE(world.isValid(id));
    EXPECT_EQ(world.joint(id).body0, 0u);  // the world's static anchor body

    // On a 1 m rope from the world point at the origin, the bob hangs 1 m below it.
    for (int i = 0; i < 30; ++i)
        physics.step(kDt);
    EXPECT_NEAR(registry.get<Transform>(bob).position.y(), -1.0, 1e-6);
    EXPECT_NEAR(registry.get<Transform>(bob).position.x(), 0.0, 1e-12);
}

TEST(PhysicsSystem, DestroyingABodyEntityRemovesItsBodyAndJoints) {
    Registry registry;
    World world = freeFallWorld();
    PhysicsSystem physics(registry, world);
    const Entity a = addBody(registry, {.shape = sphereShape(0.1), .type = BodyType::Static});
    const Entity b = addBody(registry, {.shape = sphereShape(0.1), .position = Vec3(0, -1, 0)});
    const Entity c = addBody(registry, {.shape = sphereShape(0.1), .position = Vec3(0, -2, 0)});
    const Entity ab = registry.create();
    registry.emplace<Joint>(ab, Joint{.def = {}, .body0 = a, .body1 = b});
    const Entity bc = registry.create();
    registry.emplace<Joint>(bc, Joint{.def = {}, .body0 = b, .body1 = c});
    physics.sync();
    const BodyId bodyB = registry.get<RigidBody>(b).id;
    const JointId jointAB = registry.get<Joint>(ab).id;
    const JointId jointBC = registry.get<Joint>(bc).id;
    ASSERT_EQ(liveJoints(world), 2);

    physics.destroy(b);
    EXPECT_FALSE(registry.isValid(b));
    EXPECT_FALSE(world.isValid(bodyB));
    EXPECT_FALSE(world.isValid(jointAB));
    EXPECT_FALSE(world.isValid(jointBC));
    EXPECT_EQ(liveBodies(world), 2);
    EXPECT_EQ(liveJoints(world), 0);
    // The joint components stay, dormant: their ids are cleared and sync does not revive them.
    EXPECT_TRUE(registry.get<Joint>(ab).id.isNull());
    physics.sync();
    EXPECT_TRUE(registry.get<Joint>(ab).id.isNull());
    EXPECT_TRUE(registry.get<Joint>(bc).id.isNull());
    EXPECT_EQ(liveJoints(world), 0);

    // The rest keeps simulating.
    physics.step(kDt);
    EXPECT_LT(registry.get<Transform>(c).position.y(), -2.0);
}

TEST(PhysicsSystem, DestroyingAJointEntityRemovesOnlyItsJoint) {
    Registry registry;
    World world = freeFallWorld();
    PhysicsSystem physics(registry, world);
    const Entity a = addBody(registry, {.shape = sphereShape(0.1), .type = BodyType::Static});
    const Entity b = addBody(registry, {.shape = sphereShape(0.1), .position = Vec3(0, -1, 0)});
    const Entity first = registry.create();
    registry.emplace<Joint>(first, Joint{.def = {}, .body0 = a, .body1 = b});
    const Entity second = registry.create();
    registry.emplace<Joint>(second, Joint{.def = {.maxDistance = 2.0}, .body0 = a, .body1 = b});
    physics.sync();
    const JointId firstId = registry.get<Joint>(first).id;
    const JointId secondId = registry.get<Joint>(second).id;

    physics.destroy(first);
    EXPECT_FALSE(world.isValid(firstId));
    EXPECT_TRUE(world.isValid(secondId));
    EXPECT_EQ(liveBodies(world), 2);
    EXPECT_TRUE(registry.isValid(a));
    EXPECT_TRUE(registry.isValid(b));

    physics.destroy(first);  // stale: ignored
    EXPECT_TRUE(world.isValid(secondId));
}

TEST(PhysicsSystem, EntityCreatedAfterADestroyGetsItsOwnBody) {
    Registry registry;
    World world = freeFallWorld();
    PhysicsSystem physics(registry, world);
    const Entity first = addBody(registry, {.shape = sphereShape(0.1)});
    physics.sync();
    const BodyId firstBody = registry.get<RigidBody>(first).id;
    physics.destroy(first);
    const Entity second = addBody(registry, {.shape = sphereShape(0.1), .position = Vec3(0, 7, 0)});
    physics.step(kDt);
    const BodyId secondBody = registry.get<RigidBody>(second).id;
    ASSERT_TRUE(world.isValid(secondBody));
    EXPECT_FALSE(world.isValid(firstBody));
    EXPECT_GT(registry.get<Transform>(second).position.y(), 6.9);
    EXPECT_EQ(liveBodies(world), 1);
}

}  // namespace
}  // namespace substep::ecs
