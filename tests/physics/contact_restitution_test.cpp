// Tests engine/physics/contact_restitution.cpp (and the single-point velocity pass of
// contact.cpp that uses it): an impact passes through a row of spheres as the closed forms of
// elastic and inelastic two-body collisions say, whatever order the bodies are listed in,
// touching or with gaps, floating or resting on a frictionless floor, equal or unequal masses.

#include "physics/world.h"

#include "physics_test_support.h"
#include "sphere_piles.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <cstdio>
#include <vector>

namespace substep {
namespace {

constexpr double kRadius = 0.1;
constexpr double kStrikerSpeed = 1.0;
constexpr double kStrikerGap = 0.05;  ///< m between the striker and the row

struct Row {
    std::vector<double> masses;  ///< striker first, then the row from near to far
    double gap = 0.0;            ///< between the row's spheres (m)
    double restitution = 1.0;
    bool gravity = false;
};

/// The closed form: the spheres on a line, events in time order, each the two-body collision
/// v0' = ((m0 − e m1) v0 + (1 + e) m1 v1) / (m0 + m1) (and symmetrically). Touching spheres
/// collide one pair after the other, the impact handed down the row. Returns final velocities.
std::vector<double> closedForm(const Row& row) {
    const size_t n = row.masses.size();
    std::vector<double> x(n), v(n, 0.0);
    x[0] = 0.0;
    x[1] = 2 * kRadius + kStrikerGap;
    for (size_t i = 2; i < n; ++i)
        x[i] = x[i - 1] + 2 * kRadius + row.gap;
    v[0] = kStrikerSpeed;
    for (int event = 0; event < 100000; ++event) {
        double earliest = INFINITY;
        size_t pair = n;
        for (size_t i = 0; i + 1 < n; ++i) {
            const double approach = v[i] - v[i + 1];
            if (!(approach > 1e-12)) continue;
            const double t = std::max(x[i + 1] - x[i] - 2 * kRadius, 0.0) / approach;
            if (t < earliest) earliest = t, pair = i;
        }
        if (pair == n) break;
        for (size_t i = 0; i < n; ++i)
            x[i] += v[i] * earliest;
        const double m0 = row.masses[pair], m1 = row.masses[pair + 1];
        const double v0 = v[pair], v1 = v[pair + 1], e = row.restitution;
        v[pair] = ((m0 - e * m1) * v0 + (1 + e) * m1 * v1) / (m0 + m1);
        v[pair + 1] = ((m1 - e * m0) * v1 + (1 + e) * m0 * v0) / (m0 + m1);
    }
    return v;
}

/// The row in Substep at 20 substeps, the bodies created in `order` (indices into the row,
/// 0 the striker); 1 s later, the x velocities in row order.
std::vector<double> simulate(const Row& row, const std::vector<size_t>& order) {
    World world({.gravity = row.gravity ? Vec3(0, -10, 0) : Vec3::Zero(), .substeps = 20, .sweptRestitution = true});
    const double y = row.gravity ? kRadius : 1.0;
    if (row.gravity)
        world.createBody({.shape = planeShape(Vec3::UnitY(), 0.0),
                          .type = BodyType::Static,
                          .staticFriction = 0.0,
                          .dynamicFriction = 0.0,
                          .restitution = row.restitution});
    std::vector<BodyId> ids(row.masses.size());
    for (size_t i : order) {
        double x = 0.0;
        if (i >= 1) x = 2 * kRadius + kStrikerGap + (i - 1) * (2 * kRadius + row.gap);
        ids[i] = world.createBody({.shape = sphereShape(kRadius),
                                   .mass = row.masses[i],
                                   .position = Vec3(x, y, 0),
                                   .velocity = i == 0 ? Vec3(kStrikerSpeed, 0, 0) : Vec3::Zero(),
                                   .staticFriction = 0.0,
                                   .dynamicFriction = 0.0,
                                   .restitution = row.restitution});
    }
    test::runFor(world, 1.0, [](double) {});
    std::vector<double> v;
    for (BodyId id : ids)
        v.push_back(world.body(id).v.x());
    return v;
}

/// Listing orders to try: every permutation up to six bodies (720: a striker and five), otherwise the row's order, its
/// reverse and a fixed set of shuffles.
std::vector<std::vector<size_t>> orders(size_t n) {
    std::vector<size_t> order(n);
    std::iota(order.begin(), order.end(), 0);
    std::vector<std::vector<size_t>> result;
    if (n <= 6) {
        do
            result.push_back(order);
        while (std::next_permutation(order.begin(), order.end()));
        return result;
    }
    result.push_back(order);
    result.emplace_back(order.rbegin(), order.rend());
    uint32_t seed = 12345;
    for (int k = 0; k < 24; ++k) {
        for (size_t i = n - 1; i > 0; --i) {  // Fisher-Yates with a fixed LCG
            seed = seed * 1664525u + 1013904223u;
            std::swap(order[i], order[seed % (i + 1)]);
        }
        result.push_back(order);
    }
    return result;
}

std::string describe(const std::vector<double>& v) {
    std::string text;
    for (double x : v)
        text += std::to_string(x) + " ";
    return text;
}

std::string describeOrder(const std::vector<size_t>& order) {
    std::string text;
    for (size_t i : order)
        text += std::to_string(i) + " ";
    return text;
}

void expectClosedForm(const Row& row, double tolerance) {
    const std::vector<double> expected = closedForm(row);
    double momentum = 0.0, energy = 0.0;
    for (size_t i = 0; i < expected.size(); ++i) {
        momentum += row.masses[i] * expected[i];
        energy += 0.5 * row.masses[i] * expected[i] * expected[i];
    }
    ASSERT_NEAR(momentum, row.masses[0] * kStrikerSpeed, 1e-12) << "the closed form itself";
    if (row.restitution == 1.0) {
        ASSERT_NEAR(energy, 0.5 * row.masses[0] * kStrikerSpeed * kStrikerSpeed, 1e-12);
    }
    for (const std::vector<size_t>& order : orders(row.masses.size())) {
        const std::vector<double> v = simulate(row, order);
        for (size_t i = 0; i < v.size(); ++i)
            ASSERT_NEAR(v[i], expected[i], tolerance)
                << "sphere " << i << ", listed in order " << describeOrder(order) << ": got "
                << describe(v) << "expected " << describe(expected);
    }
}

// The reported case: three touching spheres struck at 1 m/s, listed striker first then near to
// far, left −0.125, 0.27, 0.43, 0.43 m/s. The closed form is 0, 0, 0, 1.
TEST(ContactRestitutionTest, StrikerListedFirstPassesItsSpeedToTheFarSphere) {
    const Row row{.masses = {1, 1, 1, 1}};
    const std::vector<double> v = simulate(row, {0, 1, 2, 3});
    EXPECT_NEAR(v[0], 0.0, 1e-3);
    EXPECT_NEAR(v[1], 0.0, 1e-3);
    EXPECT_NEAR(v[2], 0.0, 1e-3);
    EXPECT_NEAR(v[3], 1.0, 1e-3);
}

TEST(ContactRestitutionTest, TouchingEqualRowsInEveryOrder) {
    for (size_t n = 2; n <= 6; ++n) {
        SCOPED_TRACE("row of " + std::to_string(n));
        expectClosedForm({.masses = std::vector<double>(n + 1, 0.7)}, 2e-3);
    }
}

TEST(ContactRestitutionTest, RowsWithGapsInEveryOrder) {
    for (size_t n = 2; n <= 6; ++n) {
        SCOPED_TRACE("row of " + std::to_string(n));
        expectClosedForm({.masses = std::vector<double>(n + 1, 2.0), .gap = 0.001}, 2e-3);
    }
}

TEST(ContactRestitutionTest, RowsWithTenMillimetreGapsInEveryOrder) {
    for (size_t n = 2; n <= 5; ++n) {
        SCOPED_TRACE("row of " + std::to_string(n));
        expectClosedForm({.masses = std::vector<double>(n + 1, 1.0), .gap = 0.01}, 2e-3);
        expectClosedForm({.masses = std::vector<double>(n + 1, 1.0), .gap = 0.01, .gravity = true}, 2e-3);
    }
}

TEST(ContactRestitutionTest, RowsOnAFrictionlessFloorUnderGravity) {
    for (size_t n : {2u, 4u}) {
        SCOPED_TRACE("row of " + std::to_string(n));
        expectClosedForm({.masses = std::vector<double>(n + 1, 1.0), .gravity = true}, 2e-3);
        expectClosedForm({.masses = std::vector<double>(n + 1, 1.0), .gap = 0.001, .gravity = true},
                         2e-3);
    }
}

// Unequal masses: a heavy striker keeps moving and strikes again; a light one bounces back.
TEST(ContactRestitutionTest, UnequalMassesMatchTheSequenceOfTwoBodyCollisions) {
    expectClosedForm({.masses = {3.0, 1.0, 1.0, 1.0}}, 5e-3);
    expectClosedForm({.masses = {0.5, 1.0, 2.0, 4.0}}, 5e-3);
    // Gaps of several substeps' travel: collisions closer in time than a substep are resolved
    // in the order the sweeps meet them, not in time order.
    expectClosedForm({.masses = {1.0, 2.0, 0.5, 1.5, 0.8}, .gap = 0.01}, 5e-3);
    expectClosedForm({.masses = {2.0, 1.0, 3.0}, .gravity = true}, 5e-3);
}

// Partial restitution: each collision keeps e of the approach speed.
TEST(ContactRestitutionTest, PartialRestitutionMatchesTheClosedForm) {
    expectClosedForm({.masses = {1.0, 1.0, 1.0}, .gap = 0.001, .restitution = 0.5}, 5e-3);
    expectClosedForm({.masses = {1.0, 1.0, 1.0, 1.0}, .restitution = 0.8}, 5e-3);
}


// Marbles on a track of two wires (static capsules along x), the case the sweeps first broke: a
// marble resting on the wires kept its support only through the push of its wire contacts,
// and a push that another contact carried into it (a neighbour pressing it, a larger marble
// striking it from above the wires' level) had its velocity removed with nothing in its place,
// so the marble went on into the wires.
constexpr double kWireRadius = 0.002;
constexpr double kWireHalfSpacing = 0.006;  ///< each wire's distance from the track's centre line

struct Track {
    World world;
    std::vector<BodyId> marbles;
    std::vector<double> radii;
};

/// Height above the wires' axes at which a marble of radius r rests on both.
double restingHeight(double r) {
    const double reach = r + kWireRadius;
    return std::sqrt(reach * reach - kWireHalfSpacing * kWireHalfSpacing);
}

/// Two wires 2 m long along x, a static stop sphere at x = −0.5 on the track (unless `stop` is
/// false), and marbles of the given radii touching one another in a row from the stop on (the
/// first `resting` of them), the others 5 cm behind and given `speed` towards the stop.
Track makeTrack(const Vec3& gravity, const std::vector<double>& radii, size_t resting, double speed,
                double restitution, double friction, bool sweep, bool stop = true) {
    Track track{World({.gravity = gravity, .substeps = 20, .sweptRestitution = sweep}), {}, radii};
    const Quat alongX(Eigen::AngleAxisd(-0.5 * test::kPi, Vec3::UnitZ()));
    for (double z : {-kWireHalfSpacing, kWireHalfSpacing})
        track.world.createBody({.shape = capsuleShape(kWireRadius, 2.0),
                                .type = BodyType::Static,
                                .position = Vec3(0, 0, z),
                                .orientation = alongX,
                                .staticFriction = friction,
                                .dynamicFriction = friction,
                                .restitution = restitution});
    const double stopRadius = 0.01;
    if (stop)
        track.world.createBody({.shape = sphereShape(stopRadius),
                            .type = BodyType::Static,
                            .position = Vec3(-0.5, restingHeight(stopRadius), 0),
                            .restitution = restitution});
    double x = -0.5 + stopRadius;
    for (size_t i = 0; i < radii.size(); ++i) {
        const double r = radii[i];
        // Touching its neighbour on the row (both resting on the wires): the centres' distance
        // is the sum of the radii, the heights differing when the radii do.
        const double previousRadius = i == 0 ? stopRadius : radii[i - 1];
        const double dy = restingHeight(r) - restingHeight(previousRadius);
        x += std::sqrt((previousRadius + r) * (previousRadius + r) - dy * dy) - previousRadius + r;
        if (i == resting) x += 0.05;  // the moving ones start apart
        const double centre = x - r;
        track.marbles.push_back(track.world.createBody({.shape = sphereShape(r),
                                                        .mass = 0.01,
                                                        .position = Vec3(centre, restingHeight(r), 0),
                                                        .velocity = i >= resting ? Vec3(-speed, 0, 0) : Vec3::Zero(),
                                                        .staticFriction = friction,
                                                        .dynamicFriction = friction,
                                                        .restitution = restitution}));
        x = centre + r;
    }
    return track;
}

/// The deepest a marble is into a wire (m, from the wires' closed-form surfaces).
double deepestIntoWires(const Track& track) {
    double deepest = 0.0;
    for (size_t i = 0; i < track.marbles.size(); ++i) {
        const Vec3& c = track.world.body(track.marbles[i]).userPosition();
        for (double z : {-kWireHalfSpacing, kWireHalfSpacing}) {
            const double distance = std::hypot(c.y(), c.z() - z);
            deepest = std::max(deepest, track.radii[i] + kWireRadius - distance);
        }
    }
    return deepest;
}

/// The fastest a marble moves at the end of any frame after `settle` seconds (m/s).
double fastestAfter(Track& track, double seconds, double settle, double* sink) {
    double fastest = 0.0;
    test::runFor(track.world, seconds, [&](double t) {
        *sink = std::max(*sink, deepestIntoWires(track));
        if (t > settle)
            for (BodyId id : track.marbles) fastest = std::max(fastest, track.world.body(id).v.norm());
    });
    return fastest;
}

// Failed first: three marbles (e = 0.5) queued on a track sloping 10° against a stop stay at
// rest (the closed form: v = 0). Each marble is held by its neighbour's push, a push without
// approach; the sweeps replaced it with no impulse, so every other substep each marble kept the
// g h sin 10° it gained, and the queue shook at 2.8-3.9 mm/s at frame ends (g h = 8.2 mm/s at
// 20 substeps). Resting contacts now keep Eq. 34, as with the paper's rule.
TEST(ContactRestitutionTest, AQueueOfMarblesOnWiresStaysAtRest) {
    const double slope = 10.0 * test::kPi / 180.0;
    const Vec3 gravity(-9.81 * std::sin(slope), -9.81 * std::cos(slope), 0);
    for (double friction : {0.0, 0.5})
        for (bool sweep : {false, true}) {
            SCOPED_TRACE(std::string(sweep ? "swept" : "paper") + ", friction " + std::to_string(friction));
            Track queue = makeTrack(gravity, {0.01, 0.01, 0.01}, 3, 0.0, 0.5, friction, sweep);
            double sink = 0.0;
            EXPECT_LT(fastestAfter(queue, 2.0, 0.5, &sink), 1e-3);
            // Resting depth is g h² (7e-6 m at 20 substeps), pushed out every substep.
            EXPECT_LT(sink, 1e-5);
        }
}

// A marble resting on the wires struck along the track by an equal one, both sliding
// (frictionless): the wires take no impulse along x, so this is the 1D collision,
// v' = (1 ∓ e) v / 2, and the struck marble stays on the wires.
TEST(ContactRestitutionTest, AMarbleOnWiresStruckAlongTheTrack) {
    for (double e : {1.0, 0.5})
        for (bool sweep : {false, true}) {
            SCOPED_TRACE(std::string(sweep ? "swept" : "paper") + ", e = " + std::to_string(e));
            Track track = makeTrack(Vec3(0, -9.81, 0), {0.01, 0.01}, 1, 0.5, e, 0.0, sweep, false);
            double sink = 0.0;
            test::runFor(track.world, 0.5, [&](double) { sink = std::max(sink, deepestIntoWires(track)); });
            EXPECT_NEAR(track.world.body(track.marbles[0]).v.x(), -0.5 * (1 + e) * 0.5, 2e-3);
            EXPECT_NEAR(track.world.body(track.marbles[1]).v.x(), -0.5 * (1 - e) * 0.5, 2e-3);
            EXPECT_LT(sink, 1e-5);
        }
}

using test::Pile;
using test::PileRun;
using test::runPile;

// A pile of spheres dropped into a walled box (spheres1000's layout, smaller): it must come to
// rest under either rule. Failed first: under the sweeps every contact of the pile that
// approached faster than 2 |g| h collided, and the pushes of the bodies a collision reached
// were replaced for 16 substeps; the pile's own settling kept colliding and never stopped
// (kinetic energy after 6 s: 0.146 J for 125 spheres, 0.171 J for the mixed 144, past the
// bound; 0.004 and 0.005 J now, 0.008 and 0.075 J with Eq. 34 alone). Only a pair that was
// apart in the substep before now starts a collision.
// The bounds hold for piles the test was not tuned for: over eight layouts of each pile
// (tests/stability/sphere_pile_test.cpp, starts shifted by up to 1 cm) the energy left was at
// most 7.5e-4 J per sphere, and up to 12 % of the spheres were still above 2 cm/s (a ball
// rolls on the floor or in a groove for ever: nothing but rolling resistance, which the engine
// does not have, would stop it), so the count is bounded at a fifth; a pile that keeps
// colliding, as above, has most of its spheres moving. The frictionless pile (e 0.8) is
// there only: in two of its eight layouts under the sweeps it had not settled after 6 s.
// Measured at 9 s since the frictionless pile's fix (AFrictionlessPileComesToRestWithoutGaining-
// Energy): with it the 64 (e 0.5) was still sliding down at 6 s (0.21 J, 13 moving, its energy
// falling at every frame after 3 s) and at rest by 7.9 s; at 9 s 2.8e-3 J, none moving.
TEST(ContactRestitutionTest, APileOfSpheresComesToRestUnderEitherRule) {
    const Pile piles[] = {{},
                          {.side = 4, .layers = 4, .restitution = 0.5},
                          {.side = 6, .layers = 4, .restitution = 0.3, .mixed = true}};
    for (const Pile& pile : piles)
        for (bool sweep : {false, true}) {
            const PileRun run = runPile(pile, sweep, 9.0);
            std::printf("%s pile of %zu, e %.1f%s: kinetic %.3g J, %zu moving after 9 s\n",
                        sweep ? "swept" : "paper", run.spheres, pile.restitution, pile.mixed ? " mixed" : "",
                        run.kinetic, run.moving);
            SCOPED_TRACE(std::string(sweep ? "swept" : "paper") + ", e " + std::to_string(pile.restitution));
            EXPECT_LT(run.kinetic, 1e-3 * run.spheres);
            EXPECT_LE(run.moving, run.spheres / 5);
        }
}

// A frictionless pile (75 spheres, e 0.8 and 0.5, 5 x 5 x 3) comes to rest under the sweeps and
// never gains energy once landed beyond Gauss-Seidel's few mJ. Failed first: a push between
// two bodies a collision reached is replaced by nothing, and its point kept any separation the
// substep's other pushes (the bodies' supports) gave it, so spheres wedged between neighbours
// were pushed apart at every substep, fell back and were pushed apart again: in layout 5 at
// e 0.8, 25 to 63 spheres still moving from 3 s to 12 s, the energy rising by up to 0.131 J
// in a frame (layout 1 at e 0.5: 0.057 J by 8 s, 28 moving at 12 s). Such a point now separates no
// faster than before the substep. The bound on a rise: Eq. 34 alone, over eight layouts of
// each, left rises after landing of up to 0.025 J (sixteen layouts at e 0.5 and 0.8); the
// fixed sweeps up to 0.019 J, all at rest by 5.4 s (tests/stability/sphere_pile_test.cpp).
TEST(ContactRestitutionTest, AFrictionlessPileComesToRestWithoutGainingEnergy) {
    const Pile piles[] = {{.side = 5, .layers = 3, .restitution = 0.8, .friction = 0.0, .seed = 5},
                          {.side = 5, .layers = 3, .restitution = 0.5, .friction = 0.0, .seed = 1}};
    for (const Pile& pile : piles) {
        const PileRun run = runPile(pile, true, 8.0);
        std::printf("frictionless pile, e %.1f, layout %u: last moving at %.2f s, largest rise %.3g J, kinetic %.3g J\n",
                    pile.restitution, pile.seed, run.lastMovingAt, run.largestRise, run.kinetic);
        SCOPED_TRACE("e " + std::to_string(pile.restitution));
        EXPECT_LT(run.lastMovingAt, 6.0);
        EXPECT_EQ(run.moving, 0u);
        EXPECT_LT(run.kinetic, 1e-4 * run.spheres);
        EXPECT_LT(run.largestRise, 0.03);
    }
}

// A smaller mixed pile (192 spheres, radii 0.07-0.12 m, masses 0.4-2.5 kg, e 0.3) with
// sleeping on falls asleep whole under either rule. Failed first: Eq. 34 15.9 s, the sweeps
// 32.0 s, when the sweeps replaced the pushes of every contact of a body a collision reached,
// its supports among them (9.3 s now). When a pile's last ball stops is decided by its
// arrangement: over five layouts the 192 fell asleep between 4.9 and 39.1 s, so the bound is
// 60 s; that the sweeps do not delay sleeping is a statistic over layouts
// (tests/stability/sphere_pile_test.cpp).
TEST(ContactRestitutionTest, AMixedPileFallsAsleepUnderEitherRule) {
    const Pile pile{.side = 8, .layers = 3, .restitution = 0.3, .mixed = true, .sleeping = true};
    for (bool sweep : {false, true}) {
        const PileRun run = runPile(pile, sweep, 60.0);
        std::printf("mixed pile of %zu, e %.1f: asleep at %.2f s under %s\n", run.spheres, pile.restitution,
                    run.asleepAt, sweep ? "the sweeps" : "Eq. 34");
        EXPECT_GT(run.asleepAt, 0.0) << (sweep ? "never fell asleep under the sweeps" : "never fell asleep under Eq. 34");
    }
}

// A ball resting on another resting on the ground: with e = 0.5 or 1, neither may bounce (both
// contacts approach by g h each substep, under the jitter guard's 2 |g| h) nor jitter; with
// e = 0.5 the top one dropped from 5 cm comes to the same rest.
TEST(ContactRestitutionTest, ABallRestingOnAnotherOnTheGroundStaysStill) {
    for (double e : {0.5, 1.0})
        for (bool sweep : {false, true})
            for (bool dropped : {false, true}) {
                if (dropped && e == 1.0) continue;  // elastic: it would bounce for ever
                SCOPED_TRACE(std::string(sweep ? "swept" : "paper") + ", e " + std::to_string(e) +
                             (dropped ? ", dropped" : ", placed"));
                World world({.gravity = Vec3(0, -9.81, 0), .substeps = 20, .sweptRestitution = sweep});
                world.createBody({.shape = planeShape(Vec3::UnitY(), 0.0), .type = BodyType::Static,
                                  .restitution = e});
                // Placed touching, or the top one dropped from 5 cm onto the bottom one.
                const BodyId bottom = world.createBody({.shape = sphereShape(0.1), .mass = 2.0,
                                                        .position = Vec3(0, 0.1, 0), .restitution = e});
                const BodyId top = world.createBody({.shape = sphereShape(0.08), .mass = 0.7,
                                                     .position = Vec3(0, dropped ? 0.33 : 0.28, 0),
                                                     .restitution = e});
                double fastest = 0.0;
                double lowest = INFINITY, highest = -INFINITY;
                test::runFor(world, 4.0, [&](double t) {
                    if (t < 2.0) return;
                    for (BodyId id : {bottom, top}) fastest = std::max(fastest, world.body(id).v.norm());
                    lowest = std::min(lowest, world.body(top).x.y());
                    highest = std::max(highest, world.body(top).x.y());
                });
                EXPECT_LT(fastest, 1e-3);
                EXPECT_LT(highest - lowest, 1e-5);
                EXPECT_NEAR(world.body(top).x.y(), 0.28, 1e-3);
            }
}

// A single ball dropped on the ground under the sweeps bounces to e² times its drop height
// (Eq. 34's closed form for a lone contact), for masses and coefficients not tuned for.
TEST(ContactRestitutionTest, ASingleBallBouncesToRestitutionSquaredTimesItsDrop) {
    for (double e : {0.3, 0.6, 0.9})
        for (double mass : {0.2, 2.5, 40.0}) {
            SCOPED_TRACE("e " + std::to_string(e) + ", mass " + std::to_string(mass));
            World world({.gravity = Vec3(0, -9.81, 0), .substeps = 20, .sweptRestitution = true});
            world.createBody({.shape = planeShape(Vec3::UnitY(), 0.0), .type = BodyType::Static,
                              .restitution = e});
            const double drop = 0.9;
            const BodyId ball = world.createBody({.shape = sphereShape(0.1), .mass = mass,
                                                  .position = Vec3(0, 0.1 + drop, 0), .restitution = e});
            bool bounced = false;
            double apex = 0.0;
            // Up to the first bounce's apex and a little beyond (the fall takes 0.43 s, the
            // rise at most e times that).
            test::runFor(world, 0.43 * (1.0 + e) + 0.05, [&](double) {
                const Body& b = world.body(ball);
                if (b.v.y() > 0.0) bounced = true;
                if (bounced) apex = std::max(apex, b.x.y() - 0.1);
            });
            ASSERT_TRUE(bounced);
            EXPECT_NEAR(apex, e * e * drop, 0.03 * e * e * drop + 2e-3);
        }
}

// The paper's rule, the default and `"restitution": "paper"`, still depends on the order (the
// issue's report): listed striker first, the far sphere of three leaves well below 1 m/s.
TEST(ContactRestitutionTest, ThePapersRuleAloneDependsOnTheOrder) {
    const auto farSpeed = [](bool sweep, const std::vector<size_t>& order) {
        World world({.gravity = Vec3::Zero(), .substeps = 20, .sweptRestitution = sweep});
        std::vector<BodyId> ids(4);
        for (size_t i : order)
            ids[i] = world.createBody({.shape = sphereShape(kRadius),
                                       .mass = 1.0,
                                       .position = Vec3(i == 0 ? 0.0 : kStrikerGap + 2 * kRadius * i, 1, 0),
                                       .velocity = i == 0 ? Vec3(kStrikerSpeed, 0, 0) : Vec3::Zero(),
                                       .staticFriction = 0.0,
                                       .dynamicFriction = 0.0,
                                       .restitution = 1.0});
        test::runFor(world, 1.0, [](double) {});
        return world.body(ids[3]).v.x();
    };
    EXPECT_LT(farSpeed(false, {0, 1, 2, 3}), 0.9);
    EXPECT_NEAR(farSpeed(false, {3, 2, 1, 0}), 1.0, 1e-3);
    EXPECT_NEAR(farSpeed(true, {0, 1, 2, 3}), 1.0, 1e-3);
    EXPECT_TRUE(WorldSettings{}.sweptRestitution) << "the sweeps are the default (world.h)";
}

}  // namespace
}  // namespace substep
