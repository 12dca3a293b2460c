// Tests engine/ecs/physics_system.cpp as the sandbox uses it: a scene driven through components
// only. Entities are made, stepped by the system, read back (Transform, velocities, joint
// readouts) and changed by Registry::patch; the world follows every change (a compliance, a
// limit, a drive, a velocity, a pose, a friction) and loses the bodies and joints of destroyed
// entities. Physics is checked against closed forms: a spring's elongation is α m g and its force
// m g; a body set moving keeps v − g t; a hinge driven to a target holds it.

#include "ecs/body_components.h"
#include "ecs/components.h"
#include "ecs/joint_pose.h"
#include "ecs/physics_system.h"
#include "ecs/registry.h"
#include "physics/world.h"

#include <gtest/gtest.h>

#include <cmath>

namespace substep::ecs {
namespace {

constexpr double kG = 10.0;
constexpr double kDt = 1.0 / 60.0;
constexpr double kMass = 2.0;

/// A box hanging from the world on a zero-rest-length spring, made of components only.
struct SpringScene {
    Registry registry;
    World world{WorldSettings{.gravity = Vec3(0, -kG, 0), .substeps = 20, .iterations = 1}};
    Entity box;
    Entity spring;

    explicit SpringScene(double compliance) {
        box = registry.create();
        emplaceBody(registry, box,
                    {.shape = boxShape(Vec3(0.2, 0.2, 0.2)), .mass = kMass, .position = Vec3(0, -compliance * kMass * kG, 0)});
        spring = registry.create();
        // Damped (Eq. 31) so that a changed spring settles; damping leaves the rest length alone.
        registry.emplace<Joint>(spring, Joint{.def = {.type = JointType::Distance, .compliance = compliance, .linearDamping = 10.0},
                                              .body0 = kNullEntity,
                                              .body1 = box});
    }
    PhysicsSystem physics() { return PhysicsSystem(registry, world); }
    void run(double seconds) {
        for (int frame = 0; frame < static_cast<int>(std::lround(seconds / kDt)); ++frame) physics().step(kDt);
    }
    double elongation() const { return -registry.get<Transform>(box).position.y(); }
};

TEST(PhysicsSystemChanges, ComponentsReadTheSpringsClosedForm) {
    constexpr double kCompliance = 0.01;
    SpringScene scene(kCompliance);
    scene.run(3.0);
    // Elongation = compliance x force (paper 3.3.1), and the joint's force is the weight.
    EXPECT_NEAR(scene.elongation(), kCompliance * kMass * kG, 1e-6);
    const Joint& spring = scene.registry.get<Joint>(scene.spring);
    EXPECT_NEAR(spring.readout.force, kMass * kG, 1e-4);
    EXPECT_NEAR(spring.readout.error, kCompliance * kMass * kG, 1e-6);
    EXPECT_NEAR(scene.registry.get<RigidBody>(scene.box).velocity.norm(), 0.0, 1e-6);
}

TEST(PhysicsSystemChanges, APatchedComplianceChangesTheWorld) {
    constexpr double kCompliance = 0.01;
    SpringScene scene(kCompliance);
    scene.run(1.0);
    scene.registry.patch<Joint>(scene.spring, [](Joint& spring) { spring.def.compliance = 2.0 * kCompliance; });
    scene.run(4.0);
    EXPECT_NEAR(scene.elongation(), 2.0 * kCompliance * kMass * kG, 1e-5);
    EXPECT_EQ(scene.world.joint(scene.registry.get<Joint>(scene.spring).id).compliance, 2.0 * kCompliance);
}

TEST(PhysicsSystemChanges, AComponentWrittenWithoutPatchIsNotApplied) {
    // The rule the sandbox follows: changes go through patch(); get() alone is a private edit.
    SpringScene scene(0.01);
    scene.run(0.5);
    scene.registry.get<Joint>(scene.spring).def.compliance = 0.02;
    scene.run(0.5);
    EXPECT_EQ(scene.world.joint(scene.registry.get<Joint>(scene.spring).id).compliance, 0.01);
}

TEST(PhysicsSystemChanges, APatchedVelocityAndPoseStartAFreeFlight) {
    Registry registry;
    World world(WorldSettings{.gravity = Vec3(0, -kG, 0), .substeps = 10});
    PhysicsSystem physics(registry, world);
    const Entity ball = registry.create();
    emplaceBody(registry, ball, {.shape = sphereShape(0.1), .mass = 1.0});
    physics.step(kDt);
    const Vec3 start(3.0, 5.0, -1.0);
    const Vec3 launch(1.0, 4.0, 0.5);
    registry.patch<Transform>(ball, [&](Transform& transform) { transform.position = start; });
    registry.patch<RigidBody>(ball, [&](RigidBody& body) { body.velocity = launch; });
    constexpr int kFrames = 30;
    for (int frame = 0; frame < kFrames; ++frame) physics.step(kDt);
    // Symplectic Euler per substep: x = x0 + v0 t − g t²/2 − g t h/2 (h the substep).
    const double t = kFrames * kDt;
    const double h = kDt / 10;
    const Vec3 expected = start + launch * t + Vec3(0, -0.5 * kG * (t * t + t * h), 0);
    EXPECT_LT((registry.get<Transform>(ball).position - expected).norm(), 1e-9);
    EXPECT_NEAR(registry.get<RigidBody>(ball).velocity.y(), launch.y() - kG * t, 1e-9);
}

TEST(PhysicsSystemChanges, APatchedHingeTargetIsReached) {
    Registry registry;
    World world(WorldSettings{.gravity = Vec3::Zero(), .substeps = 20});
    PhysicsSystem physics(registry, world);
    const Entity bar = registry.create();
    emplaceBody(registry, bar, {.shape = boxShape(Vec3(0.4, 0.05, 0.05)), .mass = 1.0, .position = Vec3(0.2, 0, 0)});
    const Entity hinge = registry.create();
    registry.emplace<Joint>(hinge, Joint{.def = {.type = JointType::Hinge,
                                                 .anchor0 = Vec3::Zero(),
                                                 .anchor1 = Vec3(-0.2, 0, 0),
                                                 .axis0 = Vec3::UnitZ(),
                                                 .axis1 = Vec3::UnitZ(),
                                                 .targetAngle = 0.0},
                                         .body0 = kNullEntity,
                                         .body1 = bar});
    for (int frame = 0; frame < 10; ++frame) physics.step(kDt);
    for (const double target : {0.7, -1.1}) {
        registry.patch<Joint>(hinge, [&](Joint& joint) { joint.def.targetAngle = target; });
        for (int frame = 0; frame < 120; ++frame) physics.step(kDt);
        const Joint& joint = registry.get<Joint>(hinge);
        EXPECT_NEAR(joint.readout.coordinate, target, 1e-6);
        // The same angle measured from the Transforms alone.
        EXPECT_NEAR(hingeAngle(jointPose(registry, joint)), target, 1e-6);
    }
}

TEST(PhysicsSystemChanges, APatchedFrictionLetsABoxSlide) {
    // A box on a 20° incline holds with μs = 0.5 > tan 20° and slides at g (sin θ − μd cos θ)
    // once both coefficients are patched down to 0.1 (paper 3.5, 3.6).
    const double angle = 20.0 * M_PI / 180.0;
    const Vec3 down(-std::cos(angle), -std::sin(angle), 0.0);
    const Vec3 normal(-std::sin(angle), std::cos(angle), 0.0);
    Registry registry;
    World world(WorldSettings{.gravity = Vec3(0, -kG, 0), .substeps = 20});
    PhysicsSystem physics(registry, world);
    const Entity slope = registry.create();
    emplaceBody(registry, slope, {.shape = planeShape(normal, 0.0), .type = BodyType::Static});
    const Entity box = registry.create();
    const Quat tilt(Eigen::AngleAxisd(angle, Vec3::UnitZ()));
    emplaceBody(registry, box, {.shape = boxShape(Vec3(0.2, 0.2, 0.2)), .mass = 1.0,
                                .position = 0.1 * normal, .orientation = tilt,
                                .staticFriction = 0.5, .dynamicFriction = 0.5});
    for (int frame = 0; frame < 60; ++frame) physics.step(kDt);
    EXPECT_LT(registry.get<RigidBody>(box).velocity.norm(), 1e-3);
    for (const Entity body : {slope, box}) {
        registry.patch<Collider>(body, [](Collider& collider) {
            collider.staticFriction = 0.1;
            collider.dynamicFriction = 0.1;
        });
    }
    for (int frame = 0; frame < 60; ++frame) physics.step(kDt);
    const double speedBefore = registry.get<RigidBody>(box).velocity.dot(down);
    for (int frame = 0; frame < 60; ++frame) physics.step(kDt);
    const double acceleration = (registry.get<RigidBody>(box).velocity.dot(down) - speedBefore) / 1.0;
    EXPECT_NEAR(acceleration, kG * (std::sin(angle) - 0.1 * std::cos(angle)), 0.05);
}

TEST(PhysicsSystemChanges, DestroyingAnEntityTakesItsBodyAndJoints) {
    SpringScene scene(0.01);
    scene.run(0.2);
    const BodyId body = scene.registry.get<RigidBody>(scene.box).id;
    const JointId joint = scene.registry.get<Joint>(scene.spring).id;
    ASSERT_TRUE(scene.world.isValid(body));
    ASSERT_TRUE(scene.world.isValid(joint));
    scene.physics().destroy(scene.box);
    EXPECT_FALSE(scene.world.isValid(body));
    EXPECT_FALSE(scene.world.isValid(joint));
    EXPECT_FALSE(scene.registry.isValid(scene.box));
    // The spring's component stays, dormant, with a null id and a zero readout.
    EXPECT_TRUE(scene.registry.get<Joint>(scene.spring).id.isNull());
    scene.run(0.2);
    EXPECT_EQ(scene.registry.get<Joint>(scene.spring).readout.force, 0.0);
}

TEST(PhysicsSystemChanges, AJointEntityMadeLaterIsCreatedAtTheNextStep) {
    // The window's drag spring: a joint entity added to a running scene.
    SpringScene scene(0.01);
    scene.run(0.5);
    const Entity pull = scene.registry.create();
    scene.registry.emplace<Joint>(pull, Joint{.def = {.type = JointType::Distance, .anchor0 = Vec3(0, -1, 0),
                                                      .compliance = 0.01},
                                              .body0 = kNullEntity,
                                              .body1 = scene.box});
    scene.run(4.0);
    // Two springs of equal compliance in parallel, anchored 1 m apart: the box sits between
    // them, lowered by half the weight's stretch of one, α m g / 2.
    EXPECT_NEAR(scene.registry.get<Transform>(scene.box).position.y(), -0.5 - 0.5 * 0.01 * kMass * kG, 1e-5);
}

TEST(PhysicsSystemChanges, PatchesAndTheDragWakeASleepingBody) {
    // Sleeping on: the box on its spring comes to rest and sleeps; each way the sandbox changes
    // a body (a velocity patch, a pose patch, the window's drag joint) must wake it.
    SpringScene scene(0.01);
    WorldSettings settings = scene.world.settings();
    settings.sleeping = true;
    scene.world.setSettings(settings);
    scene.run(2.0);
    const BodyId id = scene.registry.get<RigidBody>(scene.box).id;  // made by the first step
    ASSERT_TRUE(scene.world.isAsleep(id));

    // A velocity patch: awake, and moving at it, slowed in one frame by the spring's damping
    // (10 1/s: a factor e^(−10 dt)) and, by under 1 %, by the spring's pull.
    scene.registry.patch<RigidBody>(scene.box, [](RigidBody& body) { body.velocity = Vec3(1.0, 0, 0); });
    scene.physics().step(kDt);
    EXPECT_FALSE(scene.world.isAsleep(id));
    EXPECT_NEAR(scene.registry.get<RigidBody>(scene.box).velocity.x(), std::exp(-10.0 * kDt), 0.01);
    scene.run(3.0);
    ASSERT_TRUE(scene.world.isAsleep(id));

    // A pose patch.
    scene.registry.patch<Transform>(scene.box, [](Transform& transform) { transform.position.x() += 0.1; });
    scene.physics().step(kDt);
    EXPECT_FALSE(scene.world.isAsleep(id));
    scene.run(3.0);
    ASSERT_TRUE(scene.world.isAsleep(id));

    // The drag: a joint entity made on the sleeping body; it ends between the two springs.
    const Entity pull = scene.registry.create();
    scene.registry.emplace<Joint>(pull, Joint{.def = {.type = JointType::Distance, .anchor0 = Vec3(0, -1, 0),
                                                      .compliance = 0.01},
                                              .body0 = kNullEntity,
                                              .body1 = scene.box});
    scene.physics().step(kDt);
    EXPECT_FALSE(scene.world.isAsleep(id));
    scene.run(4.0);
    // Asleep once slower than 0.05 m/s for 0.5 s: near the equilibrium, not exactly on it.
    EXPECT_TRUE(scene.world.isAsleep(id));
    EXPECT_NEAR(scene.registry.get<Transform>(scene.box).position.y(), -0.5 - 0.5 * 0.01 * kMass * kG, 1e-3);
}

}  // namespace
}  // namespace substep::ecs
