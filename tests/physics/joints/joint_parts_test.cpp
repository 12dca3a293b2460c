// Tests engine/physics/joints/joint_parts.h and the part lists of joint.h: every part of every
// joint type is zeroed before a substep (paper 3.3.1), and the readout sums the impulses of all
// of a joint's parts, checked where two parts carry the load together against the statics of
// the hanging body (force m g, torque m g d about the anchor, Eq. 10 and Eq. 17).

#include "physics/joints/joint_geometry.h"
#include "physics/joints/joint_solver.h"
#include "physics/world.h"

#include "physics_test_support.h"

#include <gtest/gtest.h>

#include <cmath>

namespace substep {
namespace {

using test::kPi;

/// Fills a part's multiplier and impulse with non-zero values.
void dirty(PointPart& part) { part.lambda = part.impulse = Vec3(1, 2, 3); }
void dirty(RotationPart& part) { part.lambda = part.impulse = Vec3(4, 5, 6); }
void dirty(AxisPart& part) {
    part.lambda = 7;
    part.impulse = Vec3(8, 9, 10);
}
void dirty(AnglePart& part) {
    part.lambda = 11;
    part.impulse = Vec3(12, 13, 14);
}

bool isZero(const PointPart& p) { return p.lambda.isZero(0) && p.impulse.isZero(0); }
bool isZero(const RotationPart& p) { return p.lambda.isZero(0) && p.impulse.isZero(0); }
bool isZero(const AxisPart& p) { return p.lambda == 0.0 && p.impulse.isZero(0); }
bool isZero(const AnglePart& p) { return p.lambda == 0.0 && p.impulse.isZero(0); }

// Every part each type declares, listed here by name (not through parts()), is zeroed by
// Joint::resetMultipliers: a part left out of its type's parts() keeps last substep's λ.
TEST(JointPartsTest, ResetMultipliersZeroesEveryPartOfEveryType) {
    Joint distance{.model = DistanceJoint{}};
    dirty(distance.distance().attachment);
    dirty(distance.distance().rope);
    distance.resetMultipliers();
    EXPECT_TRUE(isZero(distance.distance().attachment));
    EXPECT_TRUE(isZero(distance.distance().rope));

    Joint fixed{.model = FixedJoint{}};
    dirty(std::get<FixedJoint>(fixed.model).attachment);
    dirty(std::get<FixedJoint>(fixed.model).orientation);
    fixed.resetMultipliers();
    EXPECT_TRUE(isZero(std::get<FixedJoint>(fixed.model).attachment));
    EXPECT_TRUE(isZero(std::get<FixedJoint>(fixed.model).orientation));

    Joint hinge{.model = HingeJoint{}};
    HingeJoint& h = hinge.hinge();
    dirty(h.alignment);
    dirty(h.drivePart);
    dirty(h.limit);
    dirty(h.attachment);
    hinge.resetMultipliers();
    EXPECT_TRUE(isZero(h.alignment) && isZero(h.drivePart) && isZero(h.limit) && isZero(h.attachment));

    Joint spherical{.model = SphericalJoint{}};
    SphericalJoint& s = spherical.spherical();
    dirty(s.swing);
    dirty(s.twist);
    dirty(s.attachment);
    spherical.resetMultipliers();
    EXPECT_TRUE(isZero(s.swing) && isZero(s.twist) && isZero(s.attachment));

    Joint prismatic{.model = PrismaticJoint{}};
    PrismaticJoint& p = prismatic.prismatic();
    dirty(p.orientation);
    dirty(p.offAxis);
    dirty(p.limit);
    dirty(p.drivePart);
    prismatic.resetMultipliers();
    EXPECT_TRUE(isZero(p.orientation) && isZero(p.offAxis) && isZero(p.limit) && isZero(p.drivePart));
}

// The readout adds the linear impulses of the force parts and the angular impulses of the
// torque parts, each kind apart.
TEST(JointPartsTest, ImpulsesSumOverPartsByKind) {
    Joint joint{.model = PrismaticJoint{}};
    PrismaticJoint& p = joint.prismatic();
    p.orientation.impulse = Vec3(0, 0, 2);
    p.offAxis.impulse = Vec3(1, 0, 0);
    p.limit.impulse = Vec3(0, 3, 0);
    p.drivePart.impulse = Vec3(0, 1, 0);
    EXPECT_EQ(joint.linearImpulse(), Vec3(1, 4, 0));
    EXPECT_EQ(joint.angularImpulse(), Vec3(0, 0, 2));
    EXPECT_EQ(joint.type(), JointType::Prismatic);
}

// The definition's parameters land in the type's own struct; the twist limit's compliance
// falls back to the swing limit's.
TEST(JointPartsTest, DefinitionFillsTheTypesParameters) {
    World world;
    const BodyId box = world.createBody({.shape = boxShape(Vec3(0.1, 0.1, 0.1)), .mass = 1.0});
    const Joint& rope = world.joint(world.createJoint({.type = JointType::Distance, .body1 = box, .maxDistance = 0.7}));
    EXPECT_EQ(rope.type(), JointType::Distance);
    EXPECT_EQ(rope.distance().maxDistance, 0.7);

    const Joint& hinge = world.joint(world.createJoint({.type = JointType::Hinge, .body1 = box,
                                                        .limits = Range{-0.5, 0.25}, .limitCompliance = 0.125,
                                                        .targetAngle = 0.3, .driveCompliance = 0.0625}));
    EXPECT_EQ(hinge.type(), JointType::Hinge);
    EXPECT_TRUE(hinge.hinge().hasLimits);
    EXPECT_EQ(hinge.hinge().limits.lower, -0.5);
    EXPECT_EQ(hinge.hinge().limits.upper, 0.25);
    EXPECT_EQ(hinge.hinge().limitCompliance, 0.125);
    EXPECT_EQ(hinge.hinge().drive, JointDrive::Position);
    EXPECT_EQ(hinge.hinge().target, 0.3);
    EXPECT_EQ(hinge.hinge().driveCompliance, 0.0625);
    EXPECT_THROW((void)hinge.prismatic(), std::bad_variant_access);

    const Joint& ball = world.joint(world.createJoint({.type = JointType::Spherical, .body1 = box,
                                                       .limitCompliance = 0.5, .swingLimit = 0.75,
                                                       .twistLimits = Range{-0.25, 0.5}}));
    EXPECT_EQ(ball.type(), JointType::Spherical);
    EXPECT_TRUE(ball.spherical().hasSwingLimit);
    EXPECT_EQ(ball.spherical().swingLimit, 0.75);
    EXPECT_EQ(ball.spherical().swingCompliance, 0.5);
    EXPECT_TRUE(ball.spherical().hasTwistLimits);
    EXPECT_EQ(ball.spherical().twistLimits.lower, -0.25);
    EXPECT_EQ(ball.spherical().twistCompliance, 0.5);

    const Joint& slide = world.joint(world.createJoint({.type = JointType::Prismatic, .body1 = box,
                                                        .targetOffset = -0.2, .driveCompliance = 0.25}));
    EXPECT_EQ(slide.type(), JointType::Prismatic);
    EXPECT_FALSE(slide.prismatic().hasLimits);
    EXPECT_EQ(slide.prismatic().drive, JointDrive::Position);
    EXPECT_EQ(slide.prismatic().target, -0.2);

    EXPECT_EQ(world.joint(world.createJoint({.type = JointType::Fixed, .body1 = box})).type(), JointType::Fixed);
}

/// A box of `mass` hanging from the world by `def` (anchor at the world point `pivot`, on the
/// box at `anchor1` in its frame), run 3 s to rest.
struct Hanging {
    World world{WorldSettings{.gravity = Vec3(0, -9.81, 0), .substeps = 20}};
    BodyId box;
    JointId joint;
    Hanging(double mass, const Vec3& pivot, const Vec3& anchor1, JointDef def) {
        box = world.createBody({.shape = boxShape(Vec3(0.1, 0.1, 0.1)), .mass = mass, .position = pivot - anchor1});
        def.body1 = box;
        def.anchor0 = pivot;
        def.anchor1 = anchor1;
        joint = world.createJoint(def);
        test::runFor(world, 3.0);
    }
};

// A prismatic rail tilted 45° from the vertical, the box resting on its lower limit: the limit
// part carries m g cos 45° along the rail, the off-axis part m g sin 45° across it; the force
// read is their sum, m g, straight up on the box (a readout of one part would say m g / √2).
TEST(JointPartsTest, PrismaticForceIsLimitAndOffAxisPartsTogether) {
    const double mass = 1.5, g = 9.81;
    const Vec3 rail = Vec3(1, 1, 0).normalized();
    Hanging rig(mass, Vec3(0, 1, 0), Vec3::Zero(),
                {.type = JointType::Prismatic, .axis0 = rail, .axis1 = rail, .limits = Range{0.0, 0.5}});
    const Joint& joint = rig.world.joint(rig.joint);
    const double h = rig.world.lastSubstep();
    const Vec3 onBox = -joint.linearImpulse() / (h * h);  // body 1 feels the opposite
    EXPECT_NEAR(rig.world.jointReadout(rig.joint).force, mass * g, 1e-6 * mass * g);
    EXPECT_NEAR(onBox.y(), mass * g, 1e-6 * mass * g);
    EXPECT_NEAR(onBox.x(), 0.0, 1e-6 * mass * g);
    const PrismaticJoint& p = joint.prismatic();
    EXPECT_NEAR(p.limit.impulse.norm() / (h * h), mass * g * std::cos(kPi / 4), 1e-6 * mass * g);
    EXPECT_NEAR(p.offAxis.impulse.norm() / (h * h), mass * g * std::sin(kPi / 4), 1e-6 * mass * g);
}

// A hinge whose axis lies 60° from the lever's torque: the box hangs 0.3 m sideways (along z)
// of the anchor, so gravity's torque m g d points along x; the drive holds the part along the
// hinge axis (cos 60°), the axis alignment the rest (sin 60°). The torque read is m g d.
TEST(JointPartsTest, HingeTorqueIsDriveAndAlignmentPartsTogether) {
    const double mass = 2.0, g = 9.81, d = 0.3, tilt = kPi / 3;
    const Vec3 axis(std::cos(tilt), std::sin(tilt), 0.0);
    Hanging rig(mass, Vec3(0, 1, 0), Vec3(0, 0, -d),
                {.type = JointType::Hinge, .axis0 = axis, .axis1 = axis, .targetAngle = 0.0});
    const Joint& joint = rig.world.joint(rig.joint);
    const double h = rig.world.lastSubstep();
    const JointReadout r = rig.world.jointReadout(rig.joint);
    EXPECT_NEAR(r.force, mass * g, 1e-4 * mass * g);
    EXPECT_NEAR(r.torque, mass * g * d, 1e-4 * mass * g * d);
    const HingeJoint& hinge = joint.hinge();
    EXPECT_NEAR(hinge.drivePart.impulse.norm() / (h * h), mass * g * d * std::cos(tilt), 1e-4 * mass * g * d);
    EXPECT_NEAR(hinge.alignment.impulse.norm() / (h * h), mass * g * d * std::sin(tilt), 1e-4 * mass * g * d);
}

// AnglePart::solveLimit (Algorithm 3) between two free equal bodies turned 0.5 rad apart about
// z, limited to [−0.2, 0.2]: each turns by half the excess, 0.15 rad, towards the other, and
// an angle inside the limits moves nothing.
TEST(JointPartsTest, AngleLimitTurnsBothBodiesByHalfTheExcess) {
    Body bodies[2] = {makeBody({.shape = boxShape(Vec3(0.2, 0.2, 0.2)), .mass = 1.0}),
                      makeBody({.shape = boxShape(Vec3(0.2, 0.2, 0.2)), .mass = 1.0,
                                .orientation = Quat(Eigen::AngleAxisd(0.5, Vec3::UnitZ()))})};
    SolverContext ctx{.bodies = bodies, .h = 1.0 / 60, .invH2 = 3600.0};
    const Vec3 n = Vec3::UnitZ();
    const auto x = [&](int i) { return Vec3(bodies[i].q * Vec3::UnitX()); };
    AnglePart limit;
    limit.solveLimit(ctx, 0, 1, n, x(0), x(1), -0.2, 0.2, 0.0);
    EXPECT_NEAR(std::atan2(x(0).y(), x(0).x()), 0.15, 1e-9);  // the rotation update's series
    EXPECT_NEAR(std::atan2(x(1).y(), x(1).x()), 0.35, 1e-9);
    EXPECT_GT(limit.lambda, 0.0);
    const Quat before0 = bodies[0].q, before1 = bodies[1].q;
    AnglePart inside;
    inside.solveLimit(ctx, 0, 1, n, x(0), x(1), -0.25, 0.25, 0.0);
    EXPECT_EQ(bodies[0].q.coeffs(), before0.coeffs());
    EXPECT_EQ(bodies[1].q.coeffs(), before1.coeffs());
    EXPECT_EQ(inside.lambda, 0.0);
    EXPECT_TRUE(inside.impulse.isZero(0));
}

// The form of solveLimit that takes the bodies' rotation matrices and the measured angle (the
// one the joints call) on the same pair: each body turns by half the 0.3 rad excess; inside the
// limits nothing moves.
TEST(JointPartsTest, AngleLimitWithRotationMatricesTurnsBothBodiesByHalfTheExcess) {
    Body bodies[2] = {makeBody({.shape = boxShape(Vec3(0.2, 0.2, 0.2)), .mass = 1.0}),
                      makeBody({.shape = boxShape(Vec3(0.2, 0.2, 0.2)), .mass = 1.0,
                                .orientation = Quat(Eigen::AngleAxisd(0.5, Vec3::UnitZ()))})};
    SolverContext ctx{.bodies = bodies, .h = 1.0 / 60, .invH2 = 3600.0};
    const auto x = [&](int i) { return Vec3(bodies[i].q * Vec3::UnitX()); };
    const auto phi = [&] { return signedAngle(Vec3::UnitZ(), x(0), x(1)); };
    AnglePart inside;
    inside.solveLimit(ctx, 0, 1, bodies[0].q.toRotationMatrix(), bodies[1].q.toRotationMatrix(), Vec3::UnitZ(),
                      phi(), -0.5, 0.5, 0.0);
    EXPECT_EQ(inside.lambda, 0.0);
    EXPECT_NEAR(phi(), 0.5, 1e-15);
    AnglePart limit;
    limit.solveLimit(ctx, 0, 1, bodies[0].q.toRotationMatrix(), bodies[1].q.toRotationMatrix(), Vec3::UnitZ(),
                     phi(), -0.2, 0.2, 0.0);
    EXPECT_NEAR(std::atan2(x(0).y(), x(0).x()), 0.15, 1e-9);
    EXPECT_NEAR(std::atan2(x(1).y(), x(1).x()), 0.35, 1e-9);
    EXPECT_GT(limit.lambda, 0.0);
}

// limitExcess (Algorithm 3's violation with ERRATA items 3-4): zero inside the limits, the angle
// past the bound it crossed outside, taken the short way round the circle.
TEST(JointPartsTest, LimitExcessIsTheAnglePastTheBoundTheShortWayRound) {
    EXPECT_EQ(limitExcess(0.1, -0.2, 0.3), 0.0);
    EXPECT_EQ(limitExcess(0.3, -0.2, 0.3), 0.0);
    EXPECT_NEAR(limitExcess(0.5, -0.2, 0.3), 0.2, 1e-15);
    EXPECT_NEAR(limitExcess(-0.5, -0.2, 0.3), -0.3, 1e-15);
    // 3 rad is 5 rad past an upper bound of −2 but 1.28 rad short of it the other way round.
    EXPECT_NEAR(limitExcess(3.0, -3.1, -2.0), 5.0 - 2.0 * kPi, 1e-15);
}

// frameAxis and frameNormal (joint_geometry.h) are the first two columns of the frame's rotation
// matrix, for frames turned every way.
TEST(JointGeometryTest, FrameAxisAndNormalAreTheFramesFirstColumns) {
    for (int i = 0; i < 20; ++i) {
        const Quat frame(Eigen::AngleAxisd(0.4 * i - 3.0, Vec3(std::sin(i), std::cos(3 * i), 0.5).normalized()));
        const Mat3 columns = frame.toRotationMatrix();
        EXPECT_LT((frameAxis(frame) - columns.col(0)).norm(), 1e-15);
        EXPECT_LT((frameNormal(frame) - columns.col(1)).norm(), 1e-15);
    }
}

}  // namespace
}  // namespace substep
