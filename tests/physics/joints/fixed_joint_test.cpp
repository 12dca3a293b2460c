// Tests engine/physics/joints/fixed_joint.cpp: a body welded to the world off its centre holds
// its pose under gravity and reports the static force and torque; a weld started far from its
// locked orientation turns into it without NaN.

#include "physics/world.h"

#include "physics_test_support.h"

#include <gtest/gtest.h>

#include <cmath>

namespace substep {
namespace {

using test::kDt;
using test::kPi;
using test::report;

/// A 2 kg, 0.4 x 0.1 x 0.1 m bar welded to the world by one end face, turned 0.4 rad about an
/// oblique axis; the same world axis and normal on both sides make the starting pose the locked
/// one.
struct WeldedBar {
    static constexpr double kMass = 2.0;
    static constexpr int kSubsteps = 20;
    World world{WorldSettings{.gravity = Vec3(0, -9.81, 0), .substeps = kSubsteps}};
    Quat start{Eigen::AngleAxisd(0.4, Vec3(1, 2, 3).normalized())};
    Vec3 centre{0.0, 2.0, 0.0};
    Vec3 weld;
    BodyId bar;
    JointId joint;

    WeldedBar() {
        const Vec3 end(-0.2, 0.0, 0.0);
        bar = world.createBody({.shape = boxShape(Vec3(0.4, 0.1, 0.1)),
                                .mass = kMass,
                                .position = centre,
                                .orientation = start});
        weld = centre + start * end;
        const Vec3 axis = Vec3(0.2, 1.0, -0.3).normalized(), normal = axis.cross(Vec3::UnitX());
        joint = world.createJoint({.type = JointType::Fixed,
                                   .body1 = bar,
                                   .anchor0 = weld,
                                   .anchor1 = end,
                                   .axis0 = axis,
                                   .axis1 = start.conjugate() * axis,
                                   .normal0 = normal,
                                   .normal1 = start.conjugate() * normal});
    }
    const Body& body() const { return world.body(bar); }
    double turned() const { return test::turnBetween(start, body().userOrientation()).norm(); }
    /// Static torque: m g times the horizontal lever from the weld to the centre of mass.
    double staticTorque() const {
        const Vec3 lever = centre - weld;
        return kMass * 9.81 * Vec3(lever.x(), 0.0, lever.z()).norm();
    }
};

// The welded bar holds its pose under gravity, rests, and the weld carries the weight
// m g = 19.62 N and the static torque m g |lever| = 3.713 N·m (lever: weld to centre of mass,
// horizontal part). The weld projects attachment and orientation lock as one 6 x 6 block, so a
// hard weld closes exactly every substep. Measured: pose within 1e-16 m and 6e-16 rad, torque
// 3.71299 N·m, |ω| 3e-13 rad/s.
// Regression: solved one after the other (orientation lock as a scalar correction along the
// rotation vector, then the attachment), the parts fought: the bar fluttered substep to substep
// between two orientations 1e-3 rad apart (ghost |ω| = 0.74 rad/s at every frame end), moved by
// 1.4e-4 m and read 6.977 N·m (x 1.88).
TEST(FixedJointTest, HoldsAnOffCentreBodyUnderGravity) {
    WeldedBar rig;
    double worstMove = 0.0, worstTurn = 0.0;
    test::runFor(rig.world, 2.0, [&](double) {
        worstMove = std::max(worstMove, (rig.body().userPosition() - rig.centre).norm());
        worstTurn = std::max(worstTurn, rig.turned());
    });
    report("fixed_max_move_m", worstMove);
    report("fixed_max_turn_rad", worstTurn);
    EXPECT_LT(worstMove, 1e-9);
    EXPECT_LT(worstTurn, 1e-9);
    EXPECT_LT(rig.body().omega.norm(), 1e-6);
    EXPECT_LT(rig.body().v.norm(), 1e-6);
    const JointReadout r = rig.world.jointReadout(rig.joint);
    report("fixed_torque_Nm", r.torque);
    EXPECT_NEAR(r.force, WeldedBar::kMass * 9.81, 1e-6 * WeldedBar::kMass * 9.81);
    EXPECT_NEAR(r.torque, rig.staticTorque(), 1e-6 * rig.staticTorque());
    EXPECT_LT(r.error, 1e-9);
}

// Two welded free bodies fall together: the pair keeps its relative pose exactly (the weld
// carries nothing in free fall) and its common centre of mass falls as a point would.
TEST(FixedJointTest, WeldedPairFallsAsOneBody) {
    const double g = 9.81;
    World world(WorldSettings{.gravity = Vec3(0, -g, 0), .substeps = 20});
    const BodyId a = world.createBody(
        {.shape = boxShape(Vec3(0.2, 0.2, 0.2)), .mass = 1.0, .position = Vec3(0, 5, 0)});
    const BodyId b =
        world.createBody({.shape = sphereShape(0.1), .mass = 3.0, .position = Vec3(0.2, 5, 0)});
    const JointId joint = world.createJoint({.type = JointType::Fixed,
                                             .body0 = a,
                                             .body1 = b,
                                             .anchor0 = Vec3(0.1, 0, 0),
                                             .anchor1 = Vec3(-0.1, 0, 0)});
    test::runFor(world, 1.0);
    EXPECT_NEAR((world.body(b).x - world.body(a).x).x(), 0.2, 1e-9);
    EXPECT_LT(world.body(a).omega.norm(), 1e-9);
    EXPECT_LT(world.jointReadout(joint).force, 1e-6);
}

// The body starts 170° from its locked orientation (and off its anchor): the weld turns it in by
// the exact rotation vector, never producing NaN, and ends locked.
TEST(FixedJointTest, TurnsIntoItsLockFromFarAway) {
    World world(WorldSettings{.gravity = Vec3::Zero(), .substeps = 20});
    const Quat far(Eigen::AngleAxisd(170.0 * kPi / 180.0, Vec3(0.3, 1, 0.2).normalized()));
    const BodyId body = world.createBody({.shape = boxShape(Vec3(0.3, 0.2, 0.1)),
                                          .mass = 1.0,
                                          .position = Vec3(0.1, 1.0, 0.0),
                                          .orientation = far});
    world.createJoint({.type = JointType::Fixed, .body1 = body, .anchor0 = Vec3(0, 1, 0)});
    test::runFor(world, 1.0, [&](double t) { ASSERT_TRUE(world.isFinite()) << t; });
    // Equal default frames on both sides: locked means the body's orientation is the identity
    // and its origin sits on the anchor.
    EXPECT_LT(test::turnBetween(Quat::Identity(), world.body(body).userOrientation()).norm(), 1e-4);
    EXPECT_LT((world.body(body).userPosition() - Vec3(0, 1, 0)).norm(), 1e-4);
}

}  // namespace
}  // namespace substep
