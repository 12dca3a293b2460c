// Tests engine/physics/substep_corrections.cpp: what each constraint moved in one substep, against
// closed forms. One substep of a horizontal hinge pendulum released from rest: gravity drops the
// body by c = g h²; the attachment's correction (Eqs. 2-5 with Eq. 6 and Eq. 7) lifts it by
// c / (m w) and turns it by −L (c / w) / I about the hinge axis, with w = 1/m + L²/I. A box
// resting on the ground, or on another box: each substep the contacts give every box back the
// g h² that gravity took. And the world records nothing unless asked.

#include "physics/substep_corrections.h"
#include "physics/world.h"

#include "physics/collision/shape.h"

#include <gtest/gtest.h>

#include <cmath>
#include <tuple>

namespace substep {
namespace {

constexpr double kGravity = 9.81;

/// The recorded displacement and rotation of body `index` summed over `constraints`.
std::pair<Vec3, Vec3> motionOf(std::span<const ConstraintCorrection> constraints, uint32_t index,
                               ConstraintKind kind) {
    Vec3 displacement = Vec3::Zero();
    Vec3 rotation = Vec3::Zero();
    for (const ConstraintCorrection& c : constraints) {
        if (c.kind != kind) continue;
        if (c.body0 == index) {
            displacement += c.displacement0;
            rotation += c.rotation0;
        }
        if (c.body1 == index) {
            displacement += c.displacement1;
            rotation += c.rotation1;
        }
    }
    return {displacement, rotation};
}

// (mass kg, sphere radius m, arm L m, substeps, solver)
class HingePendulumSubstep
    : public testing::TestWithParam<std::tuple<double, double, double, int, SolverType>> {};

TEST_P(HingePendulumSubstep, TheAttachmentLiftsAndTurnsTheBodyAsEqsTwoToSevenSay) {
    const auto [mass, radius, arm, substeps, solver] = GetParam();
    World world({.gravity = Vec3(0.0, -kGravity, 0.0), .substeps = substeps, .solver = solver});
    // At rest, level with the pivot: after the first substep's integration the anchor has
    // dropped by c = g h² straight down, and the gap is along y only.
    const BodyId bob = world.createBody(
        {.shape = sphereShape(radius), .mass = mass, .position = Vec3(arm, 0.0, 0.0)});
    const JointId hinge = world.createJoint({.type = JointType::Hinge,
                                             .body1 = bob,
                                             .anchor0 = Vec3::Zero(),
                                             .anchor1 = Vec3(-arm, 0.0, 0.0),
                                             .axis0 = Vec3::UnitZ(),
                                             .axis1 = Vec3::UnitZ()});
    world.recordCorrections(true);
    const double dt = 1.0 / 60.0;
    world.beginFrame(dt);
    ASSERT_TRUE(world.substep());
    const SubstepCorrections* corrections = world.corrections();
    ASSERT_NE(corrections, nullptr);
    EXPECT_EQ(corrections->substep(), 1);
    EXPECT_EQ(corrections->frameSubsteps(), substeps);
    ASSERT_EQ(corrections->constraints().size(), 1u);
    const ConstraintCorrection& c = corrections->constraints()[0];
    EXPECT_EQ(c.kind, ConstraintKind::Joint);
    EXPECT_EQ(c.index, hinge.index);

    // Eqs. 2-5: c = g h², n = +y, r = (−L, 0, 0); w = 1/m + (r × n)ᵀ I⁻¹ (r × n) = 1/m + L²/I,
    // Δλ = c / w. Eq. 6: Δx = Δλ n / m. Eq. 7: Δθ = I⁻¹ (r × Δλ n) = (0, 0, −L Δλ / I).
    const double h = dt / substeps;
    const double gap = kGravity * h * h;
    const double inertia = 0.4 * mass * radius * radius;
    const double w = 1.0 / mass + arm * arm / inertia;
    const double deltaLambda = gap / w;
    const auto [displacement, rotation] =
        motionOf(corrections->constraints(), bob.index, ConstraintKind::Joint);
    EXPECT_NEAR(displacement.y(), deltaLambda / mass, 1e-9 * gap);
    EXPECT_NEAR(displacement.x(), 0.0, 1e-9 * gap);
    EXPECT_NEAR(displacement.z(), 0.0, 1e-9 * gap);
    const double turn = -arm * deltaLambda / inertia;
    EXPECT_NEAR(rotation.z(), turn, 1e-6 * std::abs(turn));
    EXPECT_NEAR(rotation.x(), 0.0, 1e-9 * std::abs(turn));
    EXPECT_NEAR(rotation.y(), 0.0, 1e-9 * std::abs(turn));
    // The correction is what the body did in the solve: with one iteration and no other
    // constraint, the substep's start plus gravity's drop plus the correction is where it is.
    EXPECT_NEAR(world.body(bob).x.y(), -gap + deltaLambda / mass, 1e-12);
    world.endFrame();
}

INSTANTIATE_TEST_SUITE_P(
    MassesArmsAndSubsteps, HingePendulumSubstep,
    testing::Values(std::make_tuple(1.0, 0.1, 1.0, 20, SolverType::GaussSeidel),
                    std::make_tuple(0.05, 0.02, 0.3, 5, SolverType::GaussSeidel),
                    std::make_tuple(40.0, 0.5, 3.0, 50, SolverType::GaussSeidel),
                    std::make_tuple(2.0, 0.3, 0.4, 10, SolverType::Jacobi),
                    std::make_tuple(7.0, 1.0, 0.5, 1, SolverType::GaussSeidel)));

// (box size m, box mass kg, second box on top?, substeps)
class RestingBoxes : public testing::TestWithParam<std::tuple<double, double, bool, int>> {};

TEST_P(RestingBoxes, ContactsGiveEachBoxBackWhatGravityTookEverySubstep) {
    const auto [size, mass, stacked, substeps] = GetParam();
    World world({.gravity = Vec3(0.0, -kGravity, 0.0), .substeps = substeps});
    world.createBody({.shape = planeShape(Vec3::UnitY(), 0.0), .type = BodyType::Static});
    const BodyId bottom = world.createBody({.shape = boxShape(Vec3::Constant(size)),
                                            .mass = mass,
                                            .position = Vec3(0.0, size / 2, 0.0)});
    BodyId top;
    if (stacked)
        top = world.createBody({.shape = boxShape(Vec3::Constant(0.8 * size)),
                                .mass = 0.3 * mass,
                                .position = Vec3(0.0, 1.4 * size, 0.0)});
    const double dt = 1.0 / 60.0;
    for (int frame = 0; frame < 120; ++frame)
        world.step(dt);  // settle
    world.recordCorrections(true);
    const double h = dt / substeps;
    const double drop = kGravity * h * h;
    world.beginFrame(dt);
    for (int s = 0; s < substeps; ++s) {
        ASSERT_TRUE(world.substep());
        const SubstepCorrections& corrections = *world.corrections();
        EXPECT_EQ(corrections.substep(), s + 1);
        for (const BodyId box : {bottom, top}) {
            if (box.isNull()) continue;
            const auto [displacement, rotation] =
                motionOf(corrections.constraints(), box.index, ConstraintKind::Contact);
            EXPECT_NEAR(displacement.y(), drop, 0.02 * drop)
                << "box " << box.index << ", substep " << s + 1;
            EXPECT_NEAR(displacement.x(), 0.0, 0.01 * drop);
            EXPECT_NEAR(displacement.z(), 0.0, 0.01 * drop);
            EXPECT_LT(rotation.norm() * size, 0.01 * drop);
        }
    }
    EXPECT_FALSE(world.substep()) << "the frame has no substep left";
    world.endFrame();
    EXPECT_FALSE(world.frameOpen());
}

INSTANTIATE_TEST_SUITE_P(SizesMassesAndStacks, RestingBoxes,
                         testing::Values(std::make_tuple(1.0, 1.0, false, 20),
                                         std::make_tuple(0.1, 0.05, false, 10),
                                         std::make_tuple(2.0, 500.0, false, 40),
                                         std::make_tuple(0.5, 3.0, true, 20)));

TEST(SubstepCorrections, NothingIsRecordedUnlessAsked) {
    World world;
    const BodyId bob =
        world.createBody({.shape = sphereShape(0.1), .mass = 1.0, .position = Vec3(1.0, 0.0, 0.0)});
    world.createJoint({.type = JointType::Distance, .body1 = bob, .anchor1 = Vec3(-1.0, 0.0, 0.0)});
    EXPECT_EQ(world.corrections(), nullptr);
    world.step(1.0 / 60.0);
    EXPECT_EQ(world.corrections(), nullptr);
    world.recordCorrections(true);
    world.step(1.0 / 60.0);
    ASSERT_NE(world.corrections(), nullptr);
    EXPECT_EQ(world.corrections()->constraints().size(), 1u);
    EXPECT_EQ(world.corrections()->substep(), world.settings().substeps)
        << "the frame's last substep";
    world.recordCorrections(false);
    EXPECT_EQ(world.corrections(), nullptr);
}

TEST(SubstepCorrections, RotationBetweenInvertsAnExactTurn) {
    const Vec3 axis = Vec3(1.0, -2.0, 0.5).normalized();
    for (const double angle : {1e-9, 1e-4, 0.3, 2.5, -1.0}) {
        const Quat from(Eigen::AngleAxisd(0.7, Vec3(0.0, 1.0, 1.0).normalized()));
        const Quat to = Quat(Eigen::AngleAxisd(angle, axis)) * from;
        const Vec3 turn = rotationBetween(from, to);
        EXPECT_NEAR((turn - angle * axis).norm(), 0.0, 1e-12 + 1e-12 * std::abs(angle)) << angle;
        // q and −q are the same orientation: the shorter rotation is reported.
        EXPECT_NEAR((rotationBetween(from, Quat(-to.coeffs())) - angle * axis).norm(), 0.0, 1e-12)
            << angle;
    }
}

}  // namespace
}  // namespace substep
