// Tests the contact solve (engine/physics/contact.cpp, world.cpp) on what the paper names its
// weakness: a stack of 10 boxes and a pyramid of 10 rows stand for 10 s at 20 substeps with the
// top drifting less than 1 cm; and a 40-body scene of mixed shapes reruns bit for bit.

#include "physics_test_support.h"
#include "scenes/scene_registry.h"

#include <gtest/gtest.h>

#include <cstring>

namespace substep {
namespace {

BodyId namedBody(const SceneInstance& instance, const std::string& name) {
    for (const auto& [bodyName, id] : instance.namedBodyIds())
        if (bodyName == name) return id;
    return {};
}

/// Runs a built-in scene for `seconds` and returns how far the named body moved (m).
double driftOf(const char* sceneName, const char* bodyName, double seconds) {
    SceneInstance instance = buildScene(findBuiltinScene(sceneName)->build());
    const BodyId top = namedBody(instance, bodyName);
    EXPECT_FALSE(top.isNull());
    const Vec3 start = instance.world().body(top).userPosition();
    test::runFor(instance, seconds, [&](double) {});
    EXPECT_TRUE(instance.world().isFinite());
    return (instance.world().body(top).userPosition() - start).norm();
}

TEST(StackingTest, StackOfTenStandsForTenSeconds) {
    EXPECT_LT(driftOf("stack10", "box10", 10.0), 0.01);
}

TEST(StackingTest, PyramidOfTenRowsStandsForTenSeconds) {
    EXPECT_LT(driftOf("pyramid10", "r10b1", 10.0), 0.01);
}

/// 40 bodies of every primitive shape tumbling onto the ground and each other.
World mixedScene() {
    World world({.gravity = Vec3(0, -10, 0), .substeps = 20});
    world.createBody({.shape = planeShape(Vec3::UnitY(), 0.0), .type = BodyType::Static});
    for (int i = 0; i < 40; ++i) {
        const Vec3 position(0.3 * (i % 4) - 0.45, 0.5 + 0.35 * (i / 4), 0.25 * ((i * 7) % 3) - 0.25);
        const Quat orientation(Eigen::AngleAxisd(0.37 * i, Vec3(1, 2, 3).normalized()));
        Shape shape = i % 3 == 0 ? sphereShape(0.1) : i % 3 == 1 ? boxShape(Vec3(0.2, 0.15, 0.25))
                                                                : capsuleShape(0.07, 0.2);
        world.createBody({.shape = shape,
                          .mass = 0.5 + 0.1 * (i % 5),
                          .position = position,
                          .orientation = orientation,
                          .angularVelocity = Vec3(0.1 * i, 0, -0.05 * i),
                          .restitution = 0.2});
    }
    return world;
}

TEST(DeterminismTest, MixedShapesRerunBitForBit) {
    World first = mixedScene();
    World second = mixedScene();
    for (int frame = 0; frame < 180; ++frame) {
        first.step(test::kDt);
        second.step(test::kDt);
    }
    ASSERT_TRUE(first.isFinite());
    ASSERT_EQ(first.bodies().size(), second.bodies().size());
    for (size_t i = 0; i < first.bodies().size(); ++i) {
        const Body& a = first.bodies()[i];
        const Body& b = second.bodies()[i];
        EXPECT_EQ(std::memcmp(a.x.data(), b.x.data(), sizeof(double) * 3), 0) << i;
        EXPECT_EQ(std::memcmp(a.q.coeffs().data(), b.q.coeffs().data(), sizeof(double) * 4), 0) << i;
        EXPECT_EQ(std::memcmp(a.v.data(), b.v.data(), sizeof(double) * 3), 0) << i;
    }
    // The pile came to rest above the ground rather than through it.
    for (const Body& b : first.bodies())
        if (b.invMass > 0.0) {
            EXPECT_GT(b.x.y(), 0.0);
        }
}

}  // namespace
}  // namespace substep
