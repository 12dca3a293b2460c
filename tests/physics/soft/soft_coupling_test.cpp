// Tests engine/physics/soft/soft_coupling.cpp: attachments to rigid bodies (Eqs. 2-9) and
// particle contacts (Eqs. 26-30, 34), forces flowing both ways: a hinged rim with its tyre
// swings with the period of the combined inertia, a motorised rim rolls its tyre at ω r, a
// rigid ball hitting a soft box keeps the total momentum, a held box hangs where its mount is;
// which rigid bodies a soft body's particles meet (collectCandidates): never the bodies it is
// attached to, only those the collision filters let through, and every other one, a tyre resting
// on a box at its closed-form height; attachments one after the other close their gaps to a light
// body as to a heavy one, and rims whose runs are solved side by side move as each alone; the
// runs kept between substeps follow every edit of the attachments.
#include "soft_test_support.h"

#include "physics_test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <span>
#include <utility>
#include <vector>

namespace substep::test {
namespace {

/// Turns local y (the axis of cylinders and tyres) into world z.
const Quat kAxisAlongZ(Eigen::AngleAxisd(kPi / 2, Vec3::UnitX()));

TEST(SoftCoupling, HingedRimWithTyreSwingsWithTheRingsInertia) {
    // A rim (solid cylinder) carrying a tyre (a ring, I = ½ m (ro² + ri²)), hinged at d above
    // its centre: T = 2π sqrt(I_pivot / (M g d)), I_pivot = Σ (I_cm + m d²).
    const double ro = 0.35, ri = 0.25, width = 0.1, d = 0.15, theta0 = 0.1;
    const double rimDensity = 2000.0, tyreDensity = 500.0;
    World world = worldWithGround(20, false);
    const Vec3 pivot(0, 1, 0);
    const Quat tilt(Eigen::AngleAxisd(theta0, Vec3::UnitZ()));
    const Vec3 centre = pivot + tilt * Vec3(0, -d, 0);
    const BodyId rim = world.createBody({.shape = cylinderShape(ri, width),
                                         .density = rimDensity,
                                         .position = centre,
                                         .orientation = tilt * kAxisAlongZ});
    world.createJoint({.type = JointType::Hinge,
                       .body1 = rim,
                       .anchor0 = pivot,
                       .anchor1 = Vec3(0, 0, -d),  // world (0, d, 0) from the centre, before the tilt
                       .axis0 = Vec3::UnitZ(),
                       .axis1 = Vec3::UnitY()});
    SoftBodyDef tyre{.type = SoftBodyType::Tyre,
                     .outerRadius = ro,
                     .innerRadius = ri,
                     .width = width,
                     .cells = {48, 2, 2},
                     .position = centre,
                     .orientation = tilt * kAxisAlongZ,
                     .density = tyreDensity,
                     .compliance = 1e-7,
                     .collide = false};
    tyre.attachments.push_back({.body = rim, .particles = SoftAttachmentParticles::Inner});
    world.createSoftBody(tyre);

    const double mRim = rimDensity * kPi * ri * ri * width;
    const double mTyre = tyreDensity * kPi * (ro * ro - ri * ri) * width;
    const double inertia = 0.5 * mRim * ri * ri + 0.5 * mTyre * (ro * ro + ri * ri) + (mRim + mTyre) * d * d;
    const double expected = 2 * kPi * std::sqrt(inertia / ((mRim + mTyre) * kG * d)) * (1 + theta0 * theta0 / 16);
    Signal swing;
    runFor(world, 4.0, [&](double t) { swing.add(t, world.body(rim).x.x() - pivot.x()); });
    const double period = measuredPeriod(swing);
    report("period (s)", period);
    report("closed form (s)", expected);
    EXPECT_NEAR(period, expected, 0.01 * expected);
    // Without the tyre's inertia the period would be this much shorter: the test can fail.
    const double rimOnly = 2 * kPi * std::sqrt((0.5 * mRim * ri * ri + mRim * d * d) / (mRim * kG * d));
    EXPECT_GT(std::abs(rimOnly - expected), 0.05 * expected);
}

TEST(SoftCoupling, MotorisedRimRollsItsTyreAtOmegaR) {
    // A carrier slides along x on a prismatic joint; a hinge motor turns the rim at ω; the
    // tyre, pressed a little onto the ground, grips and the carrier moves at −ω r.
    const double ro = 0.3, ri = 0.2, width = 0.12, radius = 0.005, omega = 5.0;
    World world = worldWithGround();
    const double axle = ro + radius - 0.003;
    const BodyId carrier = world.createBody({.shape = boxShape(Vec3(0.1, 0.1, 0.1)),
                                             .mass = 5.0,
                                             .position = Vec3(0, axle, 0),
                                             .collide = false});
    world.createJoint({.type = JointType::Prismatic, .body1 = carrier, .anchor0 = Vec3(0, axle, 0),
                       .axis0 = Vec3::UnitX(), .axis1 = Vec3::UnitX()});
    const BodyId rim = world.createBody({.shape = cylinderShape(ri, width),
                                         .density = 1000.0,
                                         .position = Vec3(0, axle, 0),
                                         .orientation = kAxisAlongZ,
                                         .collide = false});
    world.createJoint({.type = JointType::Hinge, .body0 = carrier, .body1 = rim,
                       .axis0 = Vec3::UnitZ(), .axis1 = Vec3::UnitY(), .targetVelocity = omega});
    SoftBodyDef tyre{.type = SoftBodyType::Tyre,
                     .outerRadius = ro,
                     .innerRadius = ri,
                     .width = width,
                     .cells = {48, 2, 3},
                     .position = Vec3(0, axle, 0),
                     .orientation = kAxisAlongZ,
                     .compliance = 1e-6,
                     .damping = 5.0,
                     .staticFriction = 1.0,
                     .dynamicFriction = 0.8,
                     .particleRadius = radius};
    tyre.attachments.push_back({.body = rim, .particles = SoftAttachmentParticles::Inner});
    world.createSoftBody(tyre);
    runFor(world, 1.5);
    const double x0 = world.body(carrier).x.x();
    runFor(world, 0.5);
    const double speed = -(world.body(carrier).x.x() - x0) / 0.5;
    report("rolling speed / (omega r)", speed / (omega * ro));
    EXPECT_TRUE(world.isFinite());
    EXPECT_NEAR(speed, omega * ro, 0.03 * omega * ro);
}

TEST(SoftCoupling, BallHittingASoftBoxKeepsTheTotalMomentum) {
    World world({.gravity = Vec3::Zero(), .substeps = 20});
    const SoftBodyId box = world.createSoftBody({.size = Vec3(0.2, 0.2, 0.2), .cells = {2, 2, 2},
                                                 .compliance = 1e-5, .restitution = 0.5});
    // The ball is wider than the particle spacing: particles collide as spheres, faces do not.
    const BodyId ball = world.createBody({.shape = sphereShape(0.12), .mass = 2.0,
                                          .position = Vec3(-0.3, 0.01, 0.02), .velocity = Vec3(3, 0, 0),
                                          .restitution = 0.5});
    const Vec3 before = softMomentum(world, box) + 2.0 * world.body(ball).v;
    runFor(world, 0.5);
    const Vec3 after = softMomentum(world, box) + 2.0 * world.body(ball).v;
    EXPECT_LT((after - before).norm(), 1e-9 * before.norm());
    EXPECT_LT(world.body(ball).v.x(), 2.0);                    // the ball was slowed
    EXPECT_GT(world.softBodyReadout(box).velocity.x(), 0.5);  // and the box pushed
}

TEST(SoftCoupling, BoxHeldByItsTopLayerCarriesItsWeightToTheMount) {
    // A dynamic mount holds the particles inside it ("below") and hangs from the world on a
    // hard distance joint: the joint carries the box's weight plus the mount's.
    World world = worldWithGround(20, false);
    const BodyId mount = world.createBody({.shape = boxShape(Vec3(0.3, 0.04, 0.3)), .mass = 1.0,
                                           .position = Vec3(0, 1.1, 0), .collide = false});
    const JointId hold = world.createJoint({.type = JointType::Distance, .body1 = mount,
                                            .anchor0 = Vec3(0, 1.1, 0)});
    SoftBodyDef def{.size = Vec3(0.2, 0.2, 0.2), .cells = {2, 2, 2}, .position = Vec3(0, 1.0, 0),
                    .compliance = 1e-6, .damping = 10.0};
    def.attachments.push_back({.body = mount, .particles = SoftAttachmentParticles::Below});
    const SoftBodyId box = world.createSoftBody(def);
    const double mass = world.softBodyReadout(box).mass;
    runFor(world, 2.0);
    const double force = world.jointReadout(hold).force;
    report("hanging force / weight", force / ((mass + 1.0) * kG));
    EXPECT_NEAR(force, (mass + 1.0) * kG, 0.01 * (mass + 1.0) * kG);
    EXPECT_NEAR(world.softBodyReadout(box).centreOfMass.y(), 1.0, 0.01);
}

TEST(SoftCoupling, AttachedParticlesDoNotCollideWithTheirBody) {
    // A colliding rim 2 cm wider than the tyre's inner radius: the attached inner layer lies
    // inside it. Without gravity nothing else moves the particles, so any contact with the rim
    // would show as a contact and as particles pushed out of their places.
    const double ro = 0.3, ri = 0.2, width = 0.1;
    World world({.gravity = Vec3::Zero(), .substeps = 20});
    const BodyId rim = world.createBody({.shape = cylinderShape(ri + 0.02, width),
                                         .type = BodyType::Static,
                                         .orientation = kAxisAlongZ});
    SoftBodyDef tyre{.type = SoftBodyType::Tyre, .outerRadius = ro, .innerRadius = ri, .width = width,
                     .cells = {24, 2, 2}, .orientation = kAxisAlongZ, .compliance = 1e-6};
    tyre.attachments.push_back({.body = rim, .particles = SoftAttachmentParticles::Inner});
    const SoftBodyId id = world.createSoftBody(tyre);
    const std::vector<Vec3> start(world.softBodyPositions(id).begin(), world.softBodyPositions(id).end());
    int contacts = 0;
    runFor(world, 0.5, [&](double) { contacts = std::max(contacts, world.activeContactCount()); });
    double moved = 0.0;
    for (size_t i = 0; i < start.size(); ++i)
        moved = std::max(moved, (world.softBodyPositions(id)[i] - start[i]).norm());
    EXPECT_EQ(contacts, 0);
    EXPECT_LT(moved, 1e-12);
}

/// A tyre of `cells` around (a multiple of 4: a particle at the bottom) on a rim that slides
/// up and down only, dropped 1 cm onto a static box: returns the rim's height above the box's
/// top after 1.5 s, with the tyre's and the box's collision groups and masks given, and the
/// particles' contact force on the last substep.
struct DroppedTyre {
    double heightAboveBox = 0.0;
    double contactForce = 0.0;
    double weight = 0.0;
};
DroppedTyre dropTyreOnBox(double ro, double ri, double radius, int cells, double rimMass, uint32_t tyreGroup,
                          uint32_t tyreMask, uint32_t boxGroup, uint32_t boxMask, bool chassisAbove) {
    World world = worldWithGround(20, false);
    const double top = 0.1;
    world.createBody({.shape = boxShape(Vec3(1.0, 0.2, 1.0)), .type = BodyType::Static,
                      .position = Vec3(0, top - 0.1, 0), .collisionGroup = boxGroup, .collisionMask = boxMask});
    const double start = top + radius + ro + 0.01;
    // The rim meets what the tyre meets, but not the tyre's own group (as a car's parts).
    const BodyId rim = world.createBody({.shape = cylinderShape(ri, 0.08), .mass = rimMass,
                                         .position = Vec3(0, start, 0), .orientation = kAxisAlongZ,
                                         .collisionGroup = tyreGroup, .collisionMask = tyreMask});
    world.createJoint({.type = JointType::Prismatic, .body1 = rim, .anchor0 = Vec3(0, start, 0),
                       .axis0 = Vec3::UnitY(), .axis1 = -Vec3::UnitZ()});  // the rim's −z is world y
    if (chassisAbove) {
        // A body of the tyre's group across its upper half (a car's chassis): it lets the tyre pass.
        world.createBody({.shape = boxShape(Vec3(0.2, 0.1, 0.2)), .type = BodyType::Static,
                          .position = Vec3(0, start + ro, 0), .collisionGroup = tyreGroup,
                          .collisionMask = tyreMask});
    }
    SoftBodyDef tyre{.type = SoftBodyType::Tyre, .outerRadius = ro, .innerRadius = ri, .width = 0.08,
                     .cells = {cells, 2, 2}, .position = Vec3(0, start, 0), .orientation = kAxisAlongZ,
                     .density = 300.0, .compliance = 1e-10, .damping = 20.0, .particleRadius = radius,
                     .collisionGroup = tyreGroup, .collisionMask = tyreMask};
    tyre.attachments.push_back({.body = rim, .particles = SoftAttachmentParticles::Inner});
    const SoftBodyId id = world.createSoftBody(tyre);
    runFor(world, 1.5);
    EXPECT_TRUE(world.isFinite());
    return {.heightAboveBox = world.body(rim).x.y() - top,
            .contactForce = world.softBodies()->contactForce(kDt / 20).y(),
            .weight = (rimMass + world.softBodyReadout(id).mass) * kG};
}

TEST(SoftCoupling, TyreRestsOnABoxAtItsRadiusWhatItsFilterLetsThrough) {
    // A stiff tyre rests on its bottom row of particles: the rim's centre is the outer radius
    // and the particle radius above the box, and the box carries the whole weight. In the
    // car's group (2, mask ~2) the tyre passes through a body of that group across its upper
    // half, and still meets the box of the default group, over radii and masses not tuned for.
    constexpr uint32_t kCar = 2;
    for (const auto& [ro, ri, radius, cells, rimMass] :
         {std::tuple{0.075, 0.05, 0.005, 48, 0.02}, std::tuple{0.3, 0.2, 0.01, 24, 0.1}}) {
        const DroppedTyre rest = dropTyreOnBox(ro, ri, radius, cells, rimMass, kCar, ~kCar, 1, ~0u, true);
        report("rest height / (ro + r)", rest.heightAboveBox / (ro + radius));
        report("contact force / weight", rest.contactForce / rest.weight);
        // Within half a particle radius: a loaded tread particle still sinks about 1 mm here
        // (its push-out is capped at 1 m/s, docs/SOFT_BODIES.md).
        EXPECT_NEAR(rest.heightAboveBox, ro + radius, 0.5 * radius);
        EXPECT_NEAR(rest.contactForce, rest.weight, 0.02 * rest.weight);
        // A box of the car's group does not stop it: it falls through, ½ g t² below the box's top.
        const DroppedTyre through = dropTyreOnBox(ro, ri, radius, cells, rimMass, kCar, ~kCar, kCar, ~kCar, false);
        EXPECT_LT(through.heightAboveBox, ro + radius - 0.5 * kG * 1.0);
        EXPECT_EQ(through.contactForce, 0.0);
    }
}

}  // namespace
}  // namespace substep::test

namespace substep::test {
namespace {

/// The largest gap between a soft body's particles and their attachment points on `body`
/// (attached "all" at creation, where the body's centre was `start` and its particles `rest`).
double largestAttachmentGap(const World& world, SoftBodyId id, BodyId body, const Vec3& start,
                            const std::vector<Vec3>& rest) {
    const auto x = world.softBodyPositions(id);
    double gap = 0.0;
    for (size_t i = 0; i < x.size(); ++i)
        gap = std::max(gap, (world.body(body).x + (rest[i] - start) - x[i]).norm());
    return gap;
}

TEST(SoftCoupling, AttachmentsOneAfterTheOtherHoldALightBodyAsAHeavyOne) {
    // A rigid particle body holds the eight corners of a rigid soft cube (0.125 kg each) and
    // starts moving at 1 m/s: one substep of 1/60 s predicts a gap g = v h at every
    // attachment. Hard attachments one after the other each close their own gap, the body
    // taking its share s = w_body / (w + w_body) of the correction: a 1 g body (s = 0.99) is
    // pulled back by the first and the other gaps are left at (1 − s) g, under 1 %; a 100 kg
    // one (s = 1.2e-3) leaves each gap at most the body's later moves, 7 s g = 0.9 %. Solved
    // four at a time against one pose (Jacobi among them) the 1 g body would be pulled back four
    // times over, 3 g past its place, and by the next four 9 g the other way (measured: 8.8 g).
    // Either way the momentum, 1 g x 1 m/s or 100 kg x 1 m/s, is kept.
    for (const double bodyMass : {0.001, 100.0}) {
        World world({.gravity = Vec3::Zero(), .substeps = 1});
        const Vec3 start(0.0, 1.0, 0.0);
        const BodyId body = world.createBody({.shape = sphereShape(0.01), .type = BodyType::Particle, .mass = bodyMass,
                                              .position = start, .velocity = Vec3(1.0, 0.0, 0.0), .collide = false});
        SoftBodyDef def{.size = Vec3(0.1, 0.1, 0.1), .cells = {1, 1, 1}, .position = start, .compliance = 0.0};
        def.attachments.push_back({.body = body, .particles = SoftAttachmentParticles::All});
        const SoftBodyId cube = world.createSoftBody(def);
        const std::vector<Vec3> rest(world.softBodyPositions(cube).begin(), world.softBodyPositions(cube).end());
        const double h = 1.0 / 60.0, gap = 1.0 * h;
        world.step(h);
        const double largest = largestAttachmentGap(world, cube, body, start, rest);
        report("largest attachment gap / v h, body of " + std::to_string(bodyMass) + " kg", largest / gap);
        EXPECT_LT(largest, 0.02 * gap) << bodyMass << " kg";
        const Vec3 momentum = bodyMass * world.body(body).v + softMomentum(world, cube);
        EXPECT_LT((momentum - Vec3(bodyMass, 0.0, 0.0)).norm(), 1e-12 * bodyMass) << bodyMass << " kg";
    }
}

/// A rim hinged above its centre at `pivot`, tilted by `tilt` about z, carrying a tyre of `around`
/// cells attached by its inner particles (`compliance` each); returns the rim and the tyre.
std::pair<BodyId, SoftBodyId> addSwingingTyre(World& world, const Vec3& pivot, double tilt, int around,
                                              double compliance = 0.0) {
    const double ro = 0.35, ri = 0.25, width = 0.1, d = 0.15;
    const Quat turn(Eigen::AngleAxisd(tilt, Vec3::UnitZ()));
    const Vec3 centre = pivot + turn * Vec3(0, -d, 0);
    const BodyId rim = world.createBody({.shape = cylinderShape(ri, width), .density = 2000.0, .position = centre,
                                         .orientation = turn * kAxisAlongZ, .collide = false});
    world.createJoint({.type = JointType::Hinge, .body1 = rim, .anchor0 = pivot, .anchor1 = Vec3(0, 0, -d),
                       .axis0 = Vec3::UnitZ(), .axis1 = Vec3::UnitY()});
    SoftBodyDef tyre{.type = SoftBodyType::Tyre, .outerRadius = ro, .innerRadius = ri, .width = width,
                     .cells = {around, 2, 2}, .position = centre, .orientation = turn * kAxisAlongZ,
                     .density = 500.0, .compliance = 1e-7, .collide = false};
    tyre.attachments.push_back({.body = rim, .particles = SoftAttachmentParticles::Inner, .compliance = compliance});
    return {rim, world.createSoftBody(tyre)};
}

TEST(SoftCoupling, HardAttachmentsTakeTheCompliantStepsBits) {
    // A hard attachment's step skips Eq. 4's λ (nothing reads it): its impulse must be the
    // general step's bit for bit. With α = 1e-300 m/N the general step runs, and α̃ vanishes
    // against w and α̃ λ c against c²: a swinging rim and its tyre end on the same bits.
    const auto swing = [](double compliance) {
        World world = worldWithGround(20, false);
        const auto [rim, tyre] = addSwingingTyre(world, Vec3(0, 1, 0), 0.2, 30, compliance);
        for (int frame = 0; frame < 30; ++frame) world.step(1.0 / 60.0);
        const auto x = world.softBodyPositions(tyre);
        return std::pair(world.body(rim), std::vector<Vec3>(x.begin(), x.end()));
    };
    const auto [hardRim, hardTyre] = swing(0.0);
    const auto [rim, tyre] = swing(1e-300);
    EXPECT_GT(std::abs(hardRim.omega.z()), 0.1);  // it swings
    EXPECT_TRUE(hardRim.x == rim.x && hardRim.q.coeffs() == rim.q.coeffs());
    EXPECT_TRUE(hardTyre == tyre);
    // A compliance that counts gives other bits (the comparison can tell).
    EXPECT_FALSE(swing(1e-6).second == hardTyre);
}

TEST(SoftCoupling, LandingParticlesBounceWithTheirRestitution) {
    // Eq. 34 on the still ground: a contact particle's normal velocity after the velocity pass
    // is −e v̄_n, v̄_n its velocity before the substep's derivation (the last substep's, plus
    // g h). A box dropped flat from rest: its bottom layer bounces so in the substep it lands
    // (e is the mean of the box's and the ground's).
    const double e = 0.5, dt = 1.0 / 60.0, h = dt / 20;
    World world = worldWithGround(20, false);
    world.createBody({.shape = planeShape(Vec3::UnitY(), 0.0), .type = BodyType::Static, .restitution = e});
    const SoftBodyId box = world.createSoftBody({.size = Vec3(0.2, 0.2, 0.2), .cells = {2, 2, 2},
                                                 .position = Vec3(0, 0.3, 0), .compliance = 1e-8,
                                                 .restitution = e});
    int bounced = 0;
    for (int frame = 0; frame < 30 && bounced == 0; ++frame) {
        world.beginFrame(dt);
        while (true) {
            const auto v = world.softBodies()->velocities(box);
            const std::vector<Vec3> before(v.begin(), v.end());
            if (!world.substep()) break;
            const auto x = world.softBodyPositions(box);
            for (size_t i = 0; i < before.size(); ++i) {
                if (!(x[i].y() < 0.05 && before[i].y() < -1.0 && v[i].y() > 0.0)) continue;
                EXPECT_NEAR(v[i].y(), -e * (before[i].y() - kG * h), 1e-12) << i;
                ++bounced;
            }
        }
        world.endFrame();
    }
    EXPECT_EQ(bounced, 9);  // the 3 x 3 bottom particles, all in one substep
}

TEST(SoftCoupling, RimsSolvedSideBySideMoveAsEachAlone) {
    // solveAttachments steps the runs of attachments to different bodies in turn, link by link
    // (four at a time, here a second group of one): five swinging rims of unequal runs in one
    // world move as each does alone, bit for bit, their poses and tyres.
    const int arounds[] = {24, 30, 24, 36, 28};
    const auto pivot = [](int k) { return Vec3(2.0 * k, 1, 0); };
    const auto tilt = [](int k) { return 0.05 + 0.04 * k; };
    const auto swing = [](World& world) {
        for (int frame = 0; frame < 30; ++frame) world.step(1.0 / 60.0);
    };
    World together = worldWithGround(20, false);
    std::vector<std::pair<BodyId, SoftBodyId>> parts;
    for (int k = 0; k < 5; ++k) parts.push_back(addSwingingTyre(together, pivot(k), tilt(k), arounds[k]));
    const Vec3 start = together.body(parts[4].first).x;
    swing(together);
    // The rims swung: the comparison is not of poses at rest.
    EXPECT_GT((together.body(parts[4].first).x - start).norm(), 1e-3);
    for (int k = 0; k < 5; ++k) {
        World alone = worldWithGround(20, false);
        const auto [rim, tyre] = addSwingingTyre(alone, pivot(k), tilt(k), arounds[k]);
        swing(alone);
        const Body& a = alone.body(rim);
        const Body& b = together.body(parts[k].first);
        EXPECT_TRUE(a.x == b.x && a.q.coeffs() == b.q.coeffs()) << "rim " << k;
        const auto x = alone.softBodyPositions(tyre), y = together.softBodyPositions(parts[k].second);
        ASSERT_EQ(x.size(), y.size());
        EXPECT_TRUE(std::equal(x.begin(), x.end(), y.begin())) << "tyre " << k;
    }
}

/// The runs of `attachments` found afresh: each stretch of consecutive attachments to one body.
std::vector<AttachmentRun> freshRuns(std::span<const Attachment> attachments) {
    std::vector<AttachmentRun> runs;
    for (size_t k = 0; k < attachments.size(); ++k) {
        if (k == 0 || attachments[k].body != attachments[k - 1].body) {
            runs.emplace_back();
            runs.back().bodyIndex = attachments[k].body, runs.back().next = k;
            runs.back().lowParticle = runs.back().highParticle = attachments[k].particle;
        }
        AttachmentRun& run = runs.back();
        run.end = k + 1;
        run.lowParticle = std::min(run.lowParticle, attachments[k].particle);
        run.highParticle = std::max(run.highParticle, attachments[k].particle);
    }
    return runs;
}

/// Whether the soft system's kept runs are the runs of its attachments now.
::testing::AssertionResult runsAreFresh(const World& world) {
    const SoftSystem& soft = *world.softBodies();
    const std::vector<AttachmentRun> fresh = freshRuns(soft.attachments());
    const std::span<const AttachmentRun> kept = soft.attachmentRuns();
    if (kept.size() != fresh.size())
        return ::testing::AssertionFailure() << kept.size() << " runs kept, " << fresh.size() << " now";
    for (size_t r = 0; r < kept.size(); ++r) {
        const AttachmentRun &a = kept[r], &b = fresh[r];
        if (a.next != b.next || a.end != b.end || a.bodyIndex != b.bodyIndex || a.lowParticle != b.lowParticle ||
            a.highParticle != b.highParticle)
            return ::testing::AssertionFailure() << "run " << r << " of body " << a.bodyIndex << " kept, of body "
                                                 << b.bodyIndex << " now";
    }
    return ::testing::AssertionSuccess();
}

TEST(SoftCoupling, KeptAttachmentRunsFollowEveryEditOfTheAttachments) {
    // The runs the solve steps are listed when the attachments change, not every substep: after
    // each kind of edit (a soft body added, one destroyed, a rigid body destroyed) they are the
    // runs of the attachments as they are, and the world steps on with them.
    World world = worldWithGround(20, false);
    std::vector<std::pair<BodyId, SoftBodyId>> parts;
    const auto step = [&] {
        for (int frame = 0; frame < 3; ++frame) world.step(1.0 / 60.0);
    };
    for (int k = 0; k < 3; ++k) parts.push_back(addSwingingTyre(world, Vec3(2.0 * k, 1, 0), 0.1, 24 + 6 * k));
    // A tyre held by two rims: two runs of one soft body.
    const auto [second, unused] = addSwingingTyre(world, Vec3(8.0, 1, 0), 0.1, 24);
    (void)unused;
    SoftBodyDef twice{.type = SoftBodyType::Tyre, .outerRadius = 0.35, .innerRadius = 0.25, .width = 0.1,
                      .cells = {24, 2, 2}, .position = world.body(parts[1].first).x, .orientation = kAxisAlongZ,
                      .density = 500.0, .compliance = 1e-7, .collide = false};
    twice.attachments.push_back({.body = parts[1].first, .particles = SoftAttachmentParticles::Inner});
    twice.attachments.push_back({.body = second, .particles = SoftAttachmentParticles::Inner});
    const SoftBodyId shared = world.createSoftBody(twice);
    EXPECT_TRUE(runsAreFresh(world));
    EXPECT_EQ(world.softBodies()->attachmentRuns().size(), 6u);
    step();
    EXPECT_TRUE(runsAreFresh(world));

    world.destroySoftBody(parts[0].second);  // the first: every later particle moves down
    EXPECT_TRUE(runsAreFresh(world));
    EXPECT_EQ(world.softBodies()->attachmentRuns().size(), 5u);
    step();

    parts.push_back(addSwingingTyre(world, Vec3(10.0, 1, 0), 0.1, 30));  // into the freed slot
    EXPECT_TRUE(runsAreFresh(world));
    EXPECT_EQ(world.softBodies()->attachmentRuns().size(), 6u);
    step();

    world.destroyBody(second);  // a rigid body: its runs go, the shared tyre keeps the other
    EXPECT_TRUE(runsAreFresh(world));
    EXPECT_EQ(world.softBodies()->attachmentRuns().size(), 4u);
    step();

    world.destroySoftBody(shared);
    EXPECT_TRUE(runsAreFresh(world));
    EXPECT_EQ(world.softBodies()->attachmentRuns().size(), 3u);
    step();
    EXPECT_TRUE(runsAreFresh(world));
    EXPECT_TRUE(world.softBodies()->isFinite());
}

}  // namespace
}  // namespace substep::test
