// Tests engine/physics/world_snapshot.cpp: steps after World::restore repeat the steps that
// followed World::snapshot byte for byte (contacts that carry between frames, a motor's reached
// angle, soft particles), and a restore brings back the snapshot's state exactly.

#include "physics/world_snapshot.h"
#include "scenes/scene_registry.h"

#include "ecs/components.h"

#include "physics_test_support.h"

#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

namespace substep {
namespace {

/// Every body's x, q, v, ω and previous pose as raw doubles, so that a comparison is of bits.
std::vector<double> stateBits(const World& world) {
    std::vector<double> out;
    for (const Body& b : world.bodies()) {
        const double values[] = {b.x.x(),     b.x.y(),     b.x.z(),     b.q.w(),     b.q.x(),
                                 b.q.y(),     b.q.z(),     b.v.x(),     b.v.y(),     b.v.z(),
                                 b.omega.x(), b.omega.y(), b.omega.z(), b.xPrev.x(), b.xPrev.y(),
                                 b.xPrev.z(), b.qPrev.w(), b.qPrev.x(), b.qPrev.y(), b.qPrev.z()};
        out.insert(out.end(), std::begin(values), std::end(values));
    }
    for (const Joint& j : world.joints()) {
        const Vec3 impulse = j.linearImpulse();
        out.insert(out.end(), {impulse.x(), impulse.y(), impulse.z()});
    }
    return out;
}

bool sameBits(const std::vector<double>& a, const std::vector<double>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

class WorldSnapshotScene : public testing::TestWithParam<std::string> {};

/// Runs 30 frames, snapshots, runs 10 more (recording), moves on 10 further, restores and
/// reruns the 10: each rerun frame must equal the recorded one bit for bit.
TEST_P(WorldSnapshotScene, StepsAfterARestoreRepeatTheOriginalSteps) {
    SceneInstance instance = buildScene(findBuiltinScene(GetParam())->build());
    ecs::PhysicsSystem physics = instance.physics();
    for (int f = 0; f < 30; ++f) physics.step(test::kDt);
    const WorldSnapshot snapshot = physics.snapshot();
    const std::vector<double> atSnapshot = stateBits(instance.world());
    std::vector<std::vector<double>> original;
    for (int f = 0; f < 10; ++f) {
        physics.step(test::kDt);
        original.push_back(stateBits(instance.world()));
    }
    for (int f = 0; f < 10; ++f) physics.step(test::kDt);
    ASSERT_FALSE(sameBits(stateBits(instance.world()), atSnapshot)) << "the scene must move";

    physics.restore(snapshot);
    EXPECT_TRUE(sameBits(stateBits(instance.world()), atSnapshot));
    for (int f = 0; f < 10; ++f) {
        physics.step(test::kDt);
        EXPECT_TRUE(sameBits(stateBits(instance.world()), original[f])) << "frame " << f + 1 << " after the restore";
    }
}

// A pyramid (contacts resting from frame to frame), a hinge held by its drive, a chain of ball
// joints, tumbling shapes, a triple pendulum: joints and contacts of every kind.
INSTANTIATE_TEST_SUITE_P(Scenes, WorldSnapshotScene,
                         testing::Values("pyramid10", "hinge_bar", "pendulum3", "chain100", "boxes3",
                                         "joint_types"));

/// With sleeping on, a restore brings back each body's rest time and sleep flag: a stack
/// snapshotted while it still settles falls asleep again on the same frame, bit for bit.
TEST(WorldSnapshotTest, ARestoreBringsBackTheSleepState) {
    SceneDescription description = findBuiltinScene("stack10")->build();
    description.sleeping = true;
    SceneInstance instance = buildScene(description);
    ecs::PhysicsSystem physics = instance.physics();
    for (int f = 0; f < 10; ++f) physics.step(test::kDt);
    const WorldSnapshot snapshot = physics.snapshot();
    std::vector<std::vector<double>> original;
    std::vector<int> sleeping;
    for (int f = 0; f < 120; ++f) {
        physics.step(test::kDt);
        original.push_back(stateBits(instance.world()));
        sleeping.push_back(instance.world().sleepingBodyCount());
    }
    ASSERT_EQ(sleeping.front(), 0) << "the stack must still be awake at the snapshot";
    ASSERT_GT(sleeping.back(), 0) << "the stack must fall asleep within 2 s";

    physics.restore(snapshot);
    for (int f = 0; f < 120; ++f) {
        physics.step(test::kDt);
        ASSERT_EQ(instance.world().sleepingBodyCount(), sleeping[f]) << "frame " << f + 1 << " after the restore";
        ASSERT_TRUE(sameBits(stateBits(instance.world()), original[f])) << "frame " << f + 1 << " after the restore";
    }
}

TEST(WorldSnapshotTest, RestoreWritesThePosesBackIntoTheComponents) {
    SceneInstance instance = buildScene(findBuiltinScene("pendulum3")->build());
    ecs::PhysicsSystem physics = instance.physics();
    const ecs::Entity body = instance.bodyEntities.back();
    const Vec3 start = instance.registry.get<ecs::Transform>(body).position;
    const WorldSnapshot snapshot = physics.snapshot();
    for (int f = 0; f < 30; ++f) physics.step(test::kDt);
    ASSERT_GT((instance.registry.get<ecs::Transform>(body).position - start).norm(), 1e-3);
    physics.restore(snapshot);
    EXPECT_EQ(instance.registry.get<ecs::Transform>(body).position, start);
}

TEST(WorldSnapshotTest, CountsItsMemory) {
    SceneInstance instance = buildScene(findBuiltinScene("chain100")->build());
    const WorldSnapshot snapshot = instance.physics().snapshot();
    EXPECT_EQ(snapshot.bodyCount(), instance.world().bodies().size());
    EXPECT_GE(snapshot.bytes(), instance.world().bodies().size() * sizeof(Body));
}

}  // namespace
}  // namespace substep
