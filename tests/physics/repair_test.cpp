// Tests World::repairLargeViolations (engine/physics/world.cpp): hard joints that start far
// from satisfied are brought together before the frame instead of being projected inside a
// substep, where the violation / h turned into velocity.

#include "physics/world.h"

#include <gtest/gtest.h>

#include <cmath>

namespace substep {
namespace {

constexpr double kDt = 1.0 / 60.0;

/// A 5 kg, 1 m bar hinged (or welded, or slid) at its end to the world, its joint axis turned
/// `angle` away from the world's. Returns the kinetic energy after one frame.
double kineticAfterOneFrame(JointType type, double angle, bool repair) {
    WorldSettings settings{.gravity = Vec3(0, -10, 0), .substeps = 20};
    if (!repair) settings.repairDistance = settings.repairAngle = 0.0;
    World world(settings);
    const BodyId bar = world.createBody(
        {.shape = boxShape(Vec3(1, 0.1, 0.1)), .mass = 5, .position = Vec3(0.5, 2, 0)});
    world.createJoint({.type = type,
                       .body1 = bar,
                       .anchor0 = Vec3(0, 2, 0),
                       .anchor1 = Vec3(-0.5, 0, 0),
                       .axis0 = Vec3::UnitZ(),
                       .axis1 = Eigen::AngleAxisd(angle, Vec3::UnitY()) * Vec3::UnitZ()});
    world.step(kDt);
    EXPECT_TRUE(world.isFinite());
    return world.energies().kinetic;
}

// Released from rest, the bar can gain at most what one frame of falling gives it: with the
// hinge about the bar's own axis nothing falls at all. Without the repair the same start
// reached 540 J (90°) and 3 kJ (180°) in the first frame.
TEST(RepairTest, HingeStartedFarOffItsAxisGainsNoEnergy) {
    for (const double angle : {M_PI / 2, 3 * M_PI / 4, 0.999 * M_PI}) {
        SCOPED_TRACE(angle);
        EXPECT_GT(kineticAfterOneFrame(JointType::Hinge, angle, false), 10.0);  // the weak spot
        EXPECT_LT(kineticAfterOneFrame(JointType::Hinge, angle, true), 0.1);
    }
}

TEST(RepairTest, PrismaticAndFixedStartedFarOffGainNoEnergy) {
    for (const JointType type : {JointType::Prismatic, JointType::Fixed}) {
        for (const double angle : {M_PI / 2, 0.999 * M_PI}) {
            SCOPED_TRACE(angle);
            EXPECT_LT(kineticAfterOneFrame(type, angle, true), 0.1);
        }
    }
}

// Anchors 1 m apart on a hard ball joint: pulled together before the frame, at rest after it.
TEST(RepairTest, DistantAnchorsAreJoinedWithoutAKick) {
    World world(WorldSettings{.gravity = Vec3::Zero(), .substeps = 20});
    const BodyId ball =
        world.createBody({.shape = sphereShape(0.1), .mass = 1, .position = Vec3(1, 0, 0)});
    world.createJoint({.type = JointType::Spherical, .body1 = ball});
    world.step(kDt);
    EXPECT_LT(world.body(ball).x.norm(), 1e-6);
    EXPECT_LT(world.energies().kinetic, 1e-6);
}

// A body turned by hand is repaired on request, and only then: the running simulation's own
// errors are left to the substeps.
TEST(RepairTest, BodyTurnedByHandIsRepairedOnRequest) {
    for (const bool request : {false, true}) {
        SCOPED_TRACE(request);
        World world(WorldSettings{.gravity = Vec3::Zero(), .substeps = 20});
        const BodyId bar = world.createBody(
            {.shape = boxShape(Vec3(1, 0.1, 0.1)), .mass = 5, .position = Vec3(0.5, 2, 0)});
        world.createJoint({.type = JointType::Hinge,
                           .body1 = bar,
                           .anchor0 = Vec3(0, 2, 0),
                           .anchor1 = Vec3(-0.5, 0, 0),
                           .axis0 = Vec3::UnitZ(),
                           .axis1 = Vec3::UnitZ()});
        world.step(kDt);
        // Turn the bar 90° about world y around the hinge point: its axis now lies along x.
        const Body& body = world.body(bar);
        const Quat turn(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitY()));
        world.setBodyPose(bar, Vec3(0, 2, 0) + turn * (body.userPosition() - Vec3(0, 2, 0)),
                          turn * body.userOrientation());
        if (request) world.requestRepair();
        world.step(kDt);
        const double kinetic = world.energies().kinetic;
        if (request)
            EXPECT_LT(kinetic, 1e-3);
        else
            EXPECT_GT(kinetic, 10.0);  // the weak spot the repair removes
    }
}

// Compliant parts are springs, not violations: a stretched spring keeps its stretch and
// swings as a spring (the repair must not touch it).
TEST(RepairTest, StretchedSpringIsLeftToOscillate) {
    World world(WorldSettings{.gravity = Vec3::Zero(), .substeps = 20});
    const BodyId ball =
        world.createBody({.shape = sphereShape(0.1), .mass = 1, .position = Vec3(1, 0, 0)});
    world.createJoint({.type = JointType::Distance, .body1 = ball, .compliance = 0.01});
    world.step(kDt);
    // k = 100 N/m, m = 1 kg: x(t) = cos(10 t), so after one frame x = cos(1/6).
    EXPECT_NEAR(world.body(ball).x.x(), std::cos(10.0 * kDt), 2e-3);
}

}  // namespace
}  // namespace substep
