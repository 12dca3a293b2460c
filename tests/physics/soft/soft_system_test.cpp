// Tests engine/physics/soft/soft_system.cpp: the particles' substep loop and the shape-matching
// elements against closed forms (free fall, static deflection of one element and of columns,
// its linearity in the compliance and its independence of the substep count) and invariants
// (momenta of a free body, rest without jitter, recovery from being crushed flat).
#include "soft_test_support.h"

#include "physics_test_support.h"

#include <gtest/gtest.h>

#include <cstring>
#include <vector>

namespace substep::test {
namespace {

/// Shortening of a box lattice resting on the ground after `seconds` (m).
double restingDeflection(double compliance, const Vec3& size, const std::array<int, 3>& cells,
                         int substeps = 20, double seconds = 5.0) {
    World world = worldWithGround(substeps);
    const double radius = 0.005;
    const SoftBodyId box = world.createSoftBody({.size = size,
                                                 .cells = cells,
                                                 .position = Vec3(0.0, 0.5 * size.y() + radius, 0.0),
                                                 .compliance = compliance,
                                                 .damping = 20.0,
                                                 .particleRadius = radius});
    runFor(world, seconds);
    EXPECT_TRUE(world.isFinite());
    return size.y() - world.softBodyReadout(box).extent.y();
}

TEST(SoftSystem, FallsFreelyAtG) {
    World world = worldWithGround(20, false);
    const SoftBodyId box = world.createSoftBody(
        {.size = Vec3(0.2, 0.3, 0.4), .cells = {2, 3, 4}, .position = Vec3(0, 10, 0), .compliance = 1e-5});
    const double t = 1.0;
    const int frames = static_cast<int>(std::lround(t / kDt));
    runFor(world, t);
    const SoftBodyReadout r = world.softBodyReadout(box);
    const double h = kDt / 20.0;
    EXPECT_NEAR(r.velocity.y(), -kG * t, 1e-9);
    // Algorithm 2's symplectic Euler: y = y0 − ½ g t² − ½ g h t exactly.
    EXPECT_NEAR(r.centreOfMass.y(), 10.0 - 0.5 * kG * t * t - 0.5 * kG * h * t, 1e-9);
    EXPECT_NEAR(r.velocity.x(), 0.0, 1e-12);
    EXPECT_NEAR(r.extent.y(), 0.3, 1e-9);  // no deformation in free fall
    EXPECT_EQ(frames, 60);
}

TEST(SoftSystem, MassIsDensityTimesVolume) {
    World world;
    const SoftBodyId box = world.createSoftBody({.size = Vec3(0.2, 0.3, 0.4), .cells = {2, 3, 4}, .density = 700});
    const SoftBodyReadout r = world.softBodyReadout(box);
    EXPECT_NEAR(r.mass, 700 * 0.024, 1e-12);
    EXPECT_NEAR(r.volume, 0.024, 1e-14);
    EXPECT_EQ(r.elements, 24);
    EXPECT_EQ(r.particles, 3 * 4 * 5);
}

TEST(SoftSystem, SingleElementDeflectionMatchesTheClosedForm) {
    const Vec3 size(0.1, 0.1, 0.1);
    const double alpha = 2e-5;
    const double expected = closedFormDeflection(alpha, 1000.0, size, {1, 1, 1});  // 3 mm
    const double measured = restingDeflection(alpha, size, {1, 1, 1});
    report("single element deflection (mm)", 1e3 * measured);
    report("closed form (mm)", 1e3 * expected);
    EXPECT_NEAR(measured, expected, 0.02 * expected);
}

TEST(SoftSystem, ColumnDeflectionMatchesTheClosedForm) {
    // n elements stacked: δ grows with n² (a bar under its own weight), not n.
    for (int n : {2, 4}) {
        const Vec3 size(0.1, 0.1 * n, 0.1);
        const double alpha = 5e-6;
        const double expected = closedFormDeflection(alpha, 1000.0, size, {1, n, 1});
        const double measured = restingDeflection(alpha, size, {1, n, 1});
        report("column of " + std::to_string(n) + " deflection (mm)", 1e3 * measured);
        EXPECT_NEAR(measured, expected, 0.02 * expected) << n;
    }
}

TEST(SoftSystem, WideLatticeOfFlatCellsMatchesTheClosedForm) {
    // 3 x 2 x 2 cells of 0.1 x 0.05 x 0.08: uniform compression is the equilibrium of the
    // whole lattice, with the general cell's ℓ².
    const Vec3 size(0.3, 0.1, 0.16);
    const std::array<int, 3> cells = {3, 2, 2};
    const double alpha = 2e-5;
    const double expected = closedFormDeflection(alpha, 1000.0, size, cells);
    EXPECT_NEAR(restingDeflection(alpha, size, cells), expected, 0.02 * expected);
}

TEST(SoftSystem, DeflectionIsLinearInTheCompliance) {
    const Vec3 size(0.1, 0.2, 0.1);
    const double one = restingDeflection(5e-6, size, {1, 2, 1});
    const double two = restingDeflection(1e-5, size, {1, 2, 1});
    report("deflection ratio at 2 alpha / alpha", two / one);
    EXPECT_NEAR(two / one, 2.0, 0.04);
}

TEST(SoftSystem, DeflectionDoesNotDependOnTheSubstepCount) {
    const Vec3 size(0.1, 0.2, 0.1);
    const double ten = restingDeflection(1.5e-5, size, {1, 2, 1}, 10);
    const double forty = restingDeflection(1.5e-5, size, {1, 2, 1}, 40);
    report("deflection at 10 / 40 substeps", ten / forty);
    EXPECT_NEAR(ten / forty, 1.0, 0.02);
}

TEST(SoftSystem, DroppedBoxComesToRestWithoutJitter) {
    World world = worldWithGround();
    const SoftBodyId box = world.createSoftBody({.size = Vec3(0.2, 0.2, 0.2),
                                                 .cells = {2, 2, 2},
                                                 .position = Vec3(0, 0.5, 0),
                                                 .compliance = 1e-5,
                                                 .damping = 30.0,
                                                 .restitution = 0.0});
    runFor(world, 8.0);
    double fastest = 0.0;
    const double height = world.softBodyReadout(box).centreOfMass.y();
    runFor(world, 1.0, [&](double) {
        for (const Vec3& v : world.softBodies()->velocities(box)) fastest = std::max(fastest, v.norm());
    });
    report("largest particle speed at rest (m/s)", fastest);
    EXPECT_LT(fastest, 1e-3);
    EXPECT_NEAR(world.softBodyReadout(box).centreOfMass.y(), height, 1e-5);
    EXPECT_GT(height, 0.09);  // on the ground, not through it
}

TEST(SoftSystem, FreeBodyConservesMomentum) {
    // No gravity; a spinning, deforming body: the element corrections sum to zero momentum.
    World world({.gravity = Vec3::Zero(), .substeps = 20});
    const SoftBodyId box = world.createSoftBody({.size = Vec3(0.3, 0.2, 0.1),
                                                 .cells = {3, 2, 1},
                                                 .velocity = Vec3(1, 2, 3),
                                                 .angularVelocity = Vec3(4, -2, 6),
                                                 .compliance = 1e-5});
    const Vec3 before = softMomentum(world, box);
    runFor(world, 2.0);
    EXPECT_LT((softMomentum(world, box) - before).norm(), 1e-10 * before.norm());
}

TEST(SoftSystem, SpinningFreeBodyKeepsItsAngularMomentum) {
    // Each element correction keeps L exactly (the polar rotation); what PBD loses is the
    // centripetal projection's, a fraction ω² h per unit time (docs/SOFT_BODIES.md): 0.5 % here.
    World world({.gravity = Vec3::Zero(), .substeps = 20});
    const SoftBodyId box = world.createSoftBody({.size = Vec3(0.3, 0.2, 0.1),
                                                 .cells = {3, 2, 1},
                                                 .angularVelocity = Vec3(0.3, 1.0, 0.4),
                                                 .compliance = 1e-5,
                                                 .damping = 1.0});
    const Vec3 before = softAngularMomentum(world, box);
    double worst = 0.0;
    runFor(world, 5.0, [&](double) {
        worst = std::max(worst, (softAngularMomentum(world, box) - before).norm() / before.norm());
    });
    report("largest relative change of L over 5 s", worst);
    EXPECT_LT(worst, 0.01);
}

TEST(SoftSystem, SpinningFreeBodiesKeepTheirAngularMomentumAtEveryRate) {
    // The claim at spin rates, shapes and compliances nobody tuned for: a tumbling box
    // and a tyre spun about a tilted axis, rigid and soft, at 1, 5 and 10 rad/s keep L (about
    // the origin, from the particles' state) within 1 % over 5 s, and the momentum exactly.
    // Straight-line prediction loses about (ω h)² per substep here: 12 % at 5 rad/s.
    const Vec3 axis = Vec3(0.3, 1.0, 0.4).normalized();
    const Quat tilt(Eigen::AngleAxisd(0.35, Vec3(1, 0, 1).normalized()));
    for (const SoftBodyType type : {SoftBodyType::Box, SoftBodyType::Tyre}) {
        for (const double compliance : {0.0, 2e-6}) {
            for (const double rate : {1.0, 5.0, 10.0}) {
                World world({.gravity = Vec3::Zero(), .substeps = 20});
                SoftBodyDef def{
                    .type = type,
                    .size = Vec3(0.3, 0.2, 0.1),
                    .outerRadius = 0.3,
                    .innerRadius = 0.18,
                    .width = 0.12,
                    .cells = type == SoftBodyType::Box ? std::array<int, 3>{3, 2, 1}
                                                       : std::array<int, 3>{24, 2, 2},
                    .position = Vec3(0.4, -0.2, 0.1),
                    .orientation = tilt,
                    .velocity = Vec3(0.2, -0.1, 0.3),
                    .angularVelocity = rate * (type == SoftBodyType::Box
                                                   ? axis
                                                   : Vec3(tilt * Vec3(0.2, 1, 0)).normalized()),
                    .compliance = compliance,
                    .damping = compliance > 0.0 ? 2.0 : 0.0};
                const SoftBodyId body = world.createSoftBody(def);
                const Vec3 before = softAngularMomentum(world, body);
                const Vec3 momentum = softMomentum(world, body);
                double worst = 0.0;
                runFor(world, 5.0, [&](double) {
                    worst = std::max(
                        worst, (softAngularMomentum(world, body) - before).norm() / before.norm());
                });
                const std::string name = std::string(type == SoftBodyType::Box ? "box" : "tyre") +
                                         " alpha " + std::to_string(compliance) + " at " +
                                         std::to_string(rate) + " rad/s";
                report("largest relative change of L over 5 s, " + name, worst);
                EXPECT_TRUE(world.isFinite()) << name;
                EXPECT_LT(worst, 0.01) << name;
                // Exact but for rounding: 6000 substeps of positions a metre or two from the
                // origin.
                EXPECT_LT((softMomentum(world, body) - momentum).norm(), 1e-9 * momentum.norm())
                    << name;
            }
        }
    }
}

TEST(SoftSystem, CrushedFlatBoxRecoversItsVolume) {
    World world = worldWithGround();
    const double radius = 0.005;
    const SoftBodyId box = world.createSoftBody({.size = Vec3(0.2, 0.2, 0.2),
                                                 .cells = {2, 2, 2},
                                                 .position = Vec3(0, 0.1 + radius, 0),
                                                 .compliance = 1e-4,
                                                 .preserveVolume = true,
                                                 .volumeCompliance = 1e-4,
                                                 .damping = 5.0,
                                                 .particleRadius = radius});
    const double rest = world.softBodyReadout(box).volume;
    // 200 kg on a spring that holds about 13 kg over its height: crushed flat and beyond.
    const BodyId weight = world.createBody({.shape = boxShape(Vec3(0.5, 0.05, 0.5)),
                                            .mass = 200.0,
                                            .position = Vec3(0, 0.2 + 2 * radius + 0.025, 0)});
    double smallest = rest;
    bool finite = true;
    runFor(world, 2.0, [&](double) {
        smallest = std::min(smallest, world.softBodyReadout(box).volume);
        finite = finite && world.isFinite();
    });
    report("crushed volume / rest volume", smallest / rest);
    EXPECT_LT(smallest, 0.2 * rest);
    world.destroyBody(weight);
    runFor(world, 2.0, [&](double) { finite = finite && world.isFinite(); });
    const double recovered = world.softBodyReadout(box).volume;
    report("recovered volume / rest volume", recovered / rest);
    EXPECT_TRUE(finite);
    EXPECT_GT(recovered, 0.95 * rest);
}

TEST(SoftSystem, DestroyKeepsTheOtherBodies) {
    World world = worldWithGround(20, false);
    const SoftBodyId a = world.createSoftBody({.cells = {2, 2, 2}, .position = Vec3(0, 0, 0)});
    const SoftBodyId b = world.createSoftBody({.cells = {1, 1, 1}, .position = Vec3(5, 0, 0)});
    const SoftBodyId c = world.createSoftBody({.cells = {1, 2, 1}, .position = Vec3(-5, 0, 0)});
    world.destroySoftBody(a);
    EXPECT_FALSE(world.isValid(a));
    EXPECT_TRUE(world.isValid(b));
    EXPECT_NEAR(world.softBodyReadout(b).centreOfMass.x(), 5.0, 1e-12);
    EXPECT_NEAR(world.softBodyReadout(c).centreOfMass.x(), -5.0, 1e-12);
    EXPECT_NEAR(world.softBodyReadout(c).volume, 1.0, 1e-12);
    runFor(world, 0.5);
    EXPECT_NEAR(world.softBodyReadout(c).extent.y(), 1.0, 1e-9);  // elements still whole
    const SoftBodyId d = world.createSoftBody({.cells = {1, 1, 1}});
    EXPECT_EQ(d.index, a.index);
    EXPECT_NE(d.generation, a.generation);
    EXPECT_EQ(world.softBodySurface(b).triangles.size(), 12u);
}

TEST(SoftSystem, TurnedBodiesAtRestStayAtRest) {
    // Each element's rotation starts as the body's orientation times its shape's turn
    // (lattice.h): boxes and tyres created turned every which way, without gravity, keep every
    // particle where it was. An element whose rotation did not map its rest offsets to its
    // corners would pull them towards another shape.
    World world = worldWithGround(20, false);
    world.setSettings([&] {
        WorldSettings settings = world.settings();
        settings.gravity = Vec3::Zero();
        return settings;
    }());
    std::vector<SoftBodyId> bodies;
    std::vector<std::vector<Vec3>> start;
    for (int k = 0; k < 6; ++k) {
        const Quat orientation(Eigen::AngleAxisd(0.9 * k + 0.3, Vec3(1.0, 0.5 * k - 1.0, 0.7).normalized()));
        SoftBodyDef def = k % 2 == 0 ? SoftBodyDef{.size = Vec3(0.3, 0.2, 0.4), .cells = {3, 2, 4}}
                                     : SoftBodyDef{.type = SoftBodyType::Tyre, .outerRadius = 0.3, .innerRadius = 0.2,
                                                   .width = 0.15, .cells = {7 + 4 * k, 2, 3}};
        def.position = Vec3(2.0 * k, 1.0, 0.0), def.orientation = orientation, def.compliance = 1e-6;
        bodies.push_back(world.createSoftBody(def));
        const auto x = world.softBodyPositions(bodies.back());
        start.emplace_back(x.begin(), x.end());
    }
    runFor(world, 0.5);
    for (size_t k = 0; k < bodies.size(); ++k) {
        const auto x = world.softBodyPositions(bodies[k]);
        double moved = 0.0;
        for (size_t i = 0; i < x.size(); ++i) moved = std::max(moved, (x[i] - start[k][i]).norm());
        EXPECT_LT(moved, 1e-12) << "body " << k;
    }
}

TEST(SoftSystem, SameBytesForEveryThreadCount) {
    // With a worker pool each soft body's elements are projected on a thread of their own: a
    // box and three tyres dropped on the ground give the same particles, bit for bit, at 1, 2
    // and 3 threads.
    std::vector<World> worlds;
    std::vector<std::vector<SoftBodyId>> ids;
    for (const int threads : {1, 2, 3}) {
        World world = worldWithGround();
        WorldSettings settings = world.settings();
        settings.threads = threads;
        world.setSettings(settings);
        std::vector<SoftBodyId> own;
        own.push_back(world.createSoftBody({.size = Vec3(0.3, 0.2, 0.4), .cells = {3, 2, 4},
                                            .position = Vec3(0.0, 0.3, 0.0), .compliance = 1e-6}));
        for (int k = 0; k < 3; ++k)
            own.push_back(world.createSoftBody({.type = SoftBodyType::Tyre, .outerRadius = 0.3, .innerRadius = 0.2,
                                                .width = 0.15, .cells = {24, 2, 3},
                                                .position = Vec3(1.0 + k, 0.35, 0.0),
                                                .orientation = Quat(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitX())),
                                                .angularVelocity = Vec3(0, 0, -3.0 * k),
                                                .compliance = 1e-5 * (k + 1)}));
        worlds.push_back(std::move(world));
        ids.push_back(own);
    }
    for (int frame = 0; frame < 45; ++frame) {
        for (World& world : worlds) world.step(kDt);
        for (size_t w = 1; w < worlds.size(); ++w)
            for (size_t b = 0; b < ids[w].size(); ++b) {
                const auto one = worlds[0].softBodyPositions(ids[0][b]);
                const auto other = worlds[w].softBodyPositions(ids[w][b]);
                ASSERT_EQ(one.size(), other.size());
                ASSERT_EQ(std::memcmp(one.data(), other.data(), one.size() * sizeof(Vec3)), 0)
                    << w + 1 << " threads, body " << b << ", frame " << frame;
            }
    }
    EXPECT_GT(worlds[0].activeContactCount(), 20);
    EXPECT_TRUE(worlds[0].isFinite());
}

}  // namespace
}  // namespace substep::test
