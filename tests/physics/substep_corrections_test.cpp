// Tests engine/physics/substep_corrections.cpp: what each constraint moved in one substep, against
// closed forms. One substep of a horizontal hinge pendulum released from rest: gravity drops the
// body by c = g h²; the attachment's correction (Eqs. 2-5 with Eq. 6 and Eq. 7) lifts it by
// c / (m w) and turns it by −L (c / w) / I about the hinge axis, with w = 1/m + L²/I. A box
// resting on the ground, or on another box: each substep the contacts give every box back the
// g h² that gravity took. And the world records nothing unless asked.
// The velocity pass (Eqs. 29-35): a sphere sliding on the ground loses μ_d g h of speed to
// dynamic friction in a substep and gains 2.5 μ_d g h / R of spin; a sphere landing at V leaves
// with e (V + g h) (Eq. 34). Soft bodies (paper section 4, a particle standing in for a body):
// a soft box landing on the ground is lifted by its bottom particles' contacts, each by what the
// substep's motion sank it, and bounces them at e (V + g h); a box hanging from a mount by
// attachments of compliance α is pulled back by w / (w + α / h²) of gravity's g h² (Eq. 4).

#include "physics/substep_corrections.h"
#include "physics/world.h"

#include "physics/collision/shape.h"
#include "physics/soft/soft_system.h"

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

// (sphere radius m, mass kg, dynamic friction, substeps)
class SlidingSphereSubstep : public testing::TestWithParam<std::tuple<double, double, double, int>> {};

TEST_P(SlidingSphereSubstep, DynamicFrictionTakesMuGHOfSpeedAndGivesSpin) {
    const auto [radius, mass, friction, substeps] = GetParam();
    World world({.gravity = Vec3(0.0, -kGravity, 0.0), .substeps = substeps});
    // No static friction: its position step (Eqs. 27-28) would hold a slow slide, not this one.
    world.createBody({.shape = planeShape(Vec3::UnitY(), 0.0),
                      .type = BodyType::Static,
                      .staticFriction = 0.0,
                      .dynamicFriction = friction});
    const double speed = 2.0;
    const BodyId ball = world.createBody({.shape = sphereShape(radius),
                                          .mass = mass,
                                          .position = Vec3(0.0, radius, 0.0),
                                          .velocity = Vec3(speed, 0.0, 0.0),
                                          .staticFriction = 0.0,
                                          .dynamicFriction = friction});
    world.recordCorrections(true);
    const double dt = 1.0 / 60.0;
    const double h = dt / substeps;
    world.beginFrame(dt);
    ASSERT_TRUE(world.substep());
    // The contact lifts the sphere by the g h² it fell: λ_n = m g h² (w = 1/m, r ∥ n). Eq. 30
    // (ERRATA item 2): the friction impulse is μ_d λ_n / h = μ_d m g h against the slide, so the
    // centre loses μ_d g h of speed, and about the contact point r = (0, −R, 0) it turns the
    // sphere by I⁻¹ (r × p) = −2.5 μ_d g h / R about z (rolling forward).
    Vec3 dv = Vec3::Zero(), dw = Vec3::Zero();
    int entries = 0;
    for (const VelocityCorrection& c : world.corrections()->velocityChanges()) {
        ASSERT_EQ(c.kind, ConstraintKind::Contact);
        if (c.body0 == ball.index) dv += c.velocity0, dw += c.angularVelocity0;
        if (c.body1 == ball.index) dv += c.velocity1, dw += c.angularVelocity1;
        ++entries;
    }
    EXPECT_EQ(entries, 1);
    const double loss = friction * kGravity * h;
    EXPECT_NEAR(dv.x(), -loss, 1e-6 * loss);
    EXPECT_NEAR(dv.y(), 0.0, 1e-6 * loss);
    EXPECT_NEAR(dv.z(), 0.0, 1e-9 * loss);
    const double spin = -2.5 * loss / radius;
    EXPECT_NEAR(dw.z(), spin, 1e-6 * std::abs(spin));
    EXPECT_NEAR(dw.x(), 0.0, 1e-9 * std::abs(spin));
    // The change is what the velocity pass did: the speed after it.
    EXPECT_NEAR(world.body(ball).v.x(), speed - loss, 1e-9 * speed);
    world.endFrame();
}

INSTANTIATE_TEST_SUITE_P(RadiiMassesAndFrictions, SlidingSphereSubstep,
                         testing::Values(std::make_tuple(0.1, 1.0, 0.5, 20),
                                         std::make_tuple(0.02, 0.05, 0.2, 10),
                                         std::make_tuple(1.5, 300.0, 0.9, 40)));

// (landing speed m/s, restitution, substeps)
class LandingSphereSubstep : public testing::TestWithParam<std::tuple<double, double, int>> {};

TEST_P(LandingSphereSubstep, RestitutionSendsItBackAtEOfTheApproach) {
    const auto [landing, restitution, substeps] = GetParam();
    // The paper's rule (Eq. 34) recorded as one change; the default sweeps record their
    // collision apart (contact_restitution_test checks their closed forms).
    World world({.gravity = Vec3(0.0, -kGravity, 0.0), .substeps = substeps, .sweptRestitution = false});
    world.createBody({.shape = planeShape(Vec3::UnitY(), 0.0), .type = BodyType::Static,
                      .dynamicFriction = 0.0, .restitution = restitution});
    const double radius = 0.2;
    const BodyId ball = world.createBody({.shape = sphereShape(radius),
                                          .mass = 3.0,
                                          .position = Vec3(0.0, radius, 0.0),
                                          .velocity = Vec3(0.0, -landing, 0.0),
                                          .dynamicFriction = 0.0,
                                          .restitution = restitution});
    world.recordCorrections(true);
    const double dt = 1.0 / 60.0;
    const double h = dt / substeps;
    world.beginFrame(dt);
    ASSERT_TRUE(world.substep());
    // Touching at the start, the sphere sinks (V + g h) h in the substep and the contact lifts it
    // back: the derived normal velocity is 0, and Eq. 34 sets it to −e v̄_n = e (V + g h).
    ASSERT_EQ(world.corrections()->velocityChanges().size(), 1u);
    const VelocityCorrection& c = world.corrections()->velocityChanges()[0];
    const Vec3 dv = c.body0 == ball.index ? c.velocity0 : c.velocity1;
    const double bounce = restitution * (landing + kGravity * h);
    EXPECT_NEAR(dv.y(), bounce, 1e-9 * bounce + 1e-12);
    EXPECT_NEAR(dv.x(), 0.0, 1e-12);
    EXPECT_NEAR(world.body(ball).v.y(), bounce, 1e-9 * bounce + 1e-12);
    world.endFrame();
}

INSTANTIATE_TEST_SUITE_P(SpeedsAndRestitutions, LandingSphereSubstep,
                         testing::Values(std::make_tuple(3.0, 0.5, 20), std::make_tuple(0.7, 0.9, 10),
                                         std::make_tuple(12.0, 0.2, 40)));

/// The particles of soft body `id` within the soft system's storage.
std::pair<std::size_t, std::size_t> particleRange(const World& world, SoftBodyId id) {
    const std::span<const Vec3> all = world.softBodies()->particlePositions();
    const std::span<const Vec3> own = world.softBodyPositions(id);
    return {static_cast<std::size_t>(own.data() - all.data()), own.size()};
}

// (box size m, cells per side, density kg/m³, landing speed m/s, substeps)
class LandingSoftBox
    : public testing::TestWithParam<std::tuple<double, int, double, double, int>> {};

TEST_P(LandingSoftBox, BottomParticlesContactsLiftThemAndBounceThem) {
    const auto [size, cells, density, landing, substeps] = GetParam();
    const double restitution = 0.5;
    World world({.gravity = Vec3(0.0, -kGravity, 0.0), .substeps = substeps});
    world.createBody({.shape = planeShape(Vec3::UnitY(), 0.0), .type = BodyType::Static,
                      .dynamicFriction = 0.0, .restitution = restitution});
    const double radius = 0.01;
    // The bottom particles' spheres touch the ground at the start.
    const SoftBodyId box = world.createSoftBody({.size = Vec3::Constant(size),
                                                 .cells = {cells, cells, cells},
                                                 .position = Vec3(0.0, size / 2 + radius, 0.0),
                                                 .velocity = Vec3(0.0, -landing, 0.0),
                                                 .density = density,
                                                 .compliance = 1e-6,
                                                 .dynamicFriction = 0.0,
                                                 .restitution = restitution,
                                                 .particleRadius = radius});
    world.recordCorrections(true);
    const double dt = 1.0 / 60.0;
    const double h = dt / substeps;
    world.beginFrame(dt);
    ASSERT_TRUE(world.substep());
    const SubstepCorrections& corrections = *world.corrections();
    const auto [first, count] = particleRange(world, box);
    const std::span<const Vec3> contacts = corrections.particleCorrections(SoftStage::Contacts);
    const std::span<const Vec3> elements = corrections.particleCorrections(SoftStage::Elements);
    const std::span<const Vec3> bounces = corrections.particleCorrections(SoftStage::ContactVelocities);
    ASSERT_EQ(contacts.size(), world.softBodies()->particlePositions().size());
    ASSERT_EQ(bounces.size(), contacts.size());
    // Every particle falls (V + g h) h; the elements see a translation and correct nothing; the
    // bottom layer's contacts (Eq. 26, w = 1/m against a static ground: the whole depth) lift
    // each of them by that depth, and Eq. 34 sends them back at e (V + g h) (no bounce below
    // 2 g h: at rest, nothing).
    const double sink = (landing + kGravity * h) * h;
    const double bounce = landing + kGravity * h > 2.0 * kGravity * h ? restitution * (landing + kGravity * h) : 0.0;
    const std::span<const Vec3> positions = world.softBodyPositions(box);
    int bottom = 0;
    for (std::size_t i = 0; i < count; ++i) {
        const bool low = positions[i].y() < radius + 0.5 * size / cells;
        bottom += low;
        EXPECT_LT(elements[first + i].norm(), 1e-6 * sink) << i;
        EXPECT_NEAR(contacts[first + i].y(), low ? sink : 0.0, 1e-9 * sink) << i;
        EXPECT_NEAR(contacts[first + i].x(), 0.0, 1e-12) << i;
        EXPECT_NEAR(bounces[first + i].y(), low ? bounce : 0.0, 1e-9 * (bounce + 1.0)) << i;
    }
    EXPECT_EQ(bottom, (cells + 1) * (cells + 1));
    // The static ground moves not: no rigid body's entry.
    EXPECT_TRUE(corrections.constraints().empty());
    world.endFrame();
}

INSTANTIATE_TEST_SUITE_P(SizesCellsDensitiesAndSpeeds, LandingSoftBox,
                         testing::Values(std::make_tuple(0.2, 1, 1000.0, 0.0, 20),
                                         std::make_tuple(0.2, 2, 1000.0, 2.0, 20),
                                         std::make_tuple(0.05, 3, 200.0, 0.5, 10),
                                         std::make_tuple(1.0, 2, 3000.0, 5.0, 40)));

// (attachment compliance m/N, cells per side, substeps)
class HangingSoftBox : public testing::TestWithParam<std::tuple<double, int, int>> {};

TEST_P(HangingSoftBox, AttachmentsPullEachParticleBackByEqFour) {
    const auto [compliance, cells, substeps] = GetParam();
    World world({.gravity = Vec3(0.0, -kGravity, 0.0), .substeps = substeps});
    const double size = 0.3;
    const BodyId mount = world.createBody({.shape = boxShape(Vec3::Constant(size)),
                                           .type = BodyType::Static,
                                           .position = Vec3(0.0, 1.0, 0.0),
                                           .collide = false});
    SoftBodyDef def{.size = Vec3::Constant(size),
                    .cells = {cells, cells, cells},
                    .position = Vec3(0.0, 1.0, 0.0),
                    .compliance = 1e-6,
                    .collide = false};
    def.attachments.push_back({.body = mount, .particles = SoftAttachmentParticles::All, .compliance = compliance});
    const SoftBodyId box = world.createSoftBody(def);
    world.recordCorrections(true);
    const double dt = 1.0 / 60.0;
    const double h = dt / substeps;
    world.beginFrame(dt);
    ASSERT_TRUE(world.substep());
    // Eq. 4 with λ = 0: Δλ = c / (w + α / h²), c = g h² the fall, and Eq. 6 moves the particle
    // by w Δλ (the static mount takes nothing): back up by g h² w / (w + α / h²).
    const auto [first, count] = particleRange(world, box);
    const std::span<const Vec3> attached =
        world.corrections()->particleCorrections(SoftStage::Attachments);
    const std::span<const double> masses = world.softBodies()->masses(box);
    const double fall = kGravity * h * h;
    for (std::size_t i = 0; i < count; ++i) {
        const double w = 1.0 / masses[i];
        const double back = fall * w / (w + compliance / (h * h));
        EXPECT_NEAR(attached[first + i].y(), back, 1e-9 * fall) << i;
        EXPECT_NEAR(attached[first + i].x(), 0.0, 1e-12) << i;
    }
    world.endFrame();
}

INSTANTIATE_TEST_SUITE_P(CompliancesAndCells, HangingSoftBox,
                         testing::Values(std::make_tuple(0.0, 1, 20), std::make_tuple(1e-4, 2, 20),
                                         std::make_tuple(1e-6, 2, 5), std::make_tuple(1e-3, 3, 40)));

TEST(SubstepCorrections, SoftAttachmentsToADynamicBodyBalanceTheParticlesMomentum) {
    // A soft box flying at 1 m/s, attached to a rigid box at rest at its centre, no gravity:
    // the attachments pull the box along and the particles back. What they moved the rigid body
    // is one entry (SoftAttachments), and by Eq. 6 and Eq. 7 M Δx = −Σ m_i Δx_i.
    World world({.gravity = Vec3::Zero(), .substeps = 10});
    const double mass = 2.0;
    const BodyId carrier = world.createBody({.shape = boxShape(Vec3::Constant(0.1)),
                                             .mass = mass,
                                             .position = Vec3(0.0, 1.0, 0.0),
                                             .collide = false});
    SoftBodyDef def{.size = Vec3::Constant(0.3),
                    .cells = {2, 2, 2},
                    .position = Vec3(0.0, 1.0, 0.0),
                    .velocity = Vec3(1.0, 0.0, 0.0),
                    .compliance = 1e-6,
                    .collide = false};
    def.attachments.push_back({.body = carrier, .particles = SoftAttachmentParticles::All});
    const SoftBodyId box = world.createSoftBody(def);
    world.recordCorrections(true);
    world.beginFrame(1.0 / 60.0);
    ASSERT_TRUE(world.substep());
    const SubstepCorrections& corrections = *world.corrections();
    ASSERT_EQ(corrections.constraints().size(), 1u);
    const ConstraintCorrection& c = corrections.constraints()[0];
    EXPECT_EQ(c.kind, ConstraintKind::SoftAttachments);
    EXPECT_EQ(c.body0, carrier.index);
    const auto [first, count] = particleRange(world, box);
    const std::span<const Vec3> attached = corrections.particleCorrections(SoftStage::Attachments);
    const std::span<const double> masses = world.softBodies()->masses(box);
    Vec3 momentum = Vec3::Zero();
    for (std::size_t i = 0; i < count; ++i) momentum += masses[i] * attached[first + i];
    EXPECT_GT(c.displacement0.x(), 0.0) << "pulled along";
    EXPECT_LT(momentum.x(), 0.0) << "the particles held back";
    EXPECT_NEAR((mass * c.displacement0 + momentum).norm(), 0.0, 1e-9 * momentum.norm());
    world.endFrame();
}

}  // namespace
}  // namespace substep
