// Tests engine/physics/contact.cpp's one-point path (solveSinglePointPositions and
// solveSinglePointVelocities, reached through solveContactPositions and solveContactVelocities)
// against what every update must satisfy whatever the rounding, over random pairs the pile
// tests never meet: the velocity pass only removes kinetic energy (Eq. 34 with e = 0 and the
// clamped Eq. 30 are dissipative), and static friction removes the substep's tangential motion
// (Eq. 27, Eq. 28) to first order without overshooting it. And solveTouchingPositions, which
// solves one-point pairs two at a time, against the list solved in order, bit for bit.

#include "physics/contact.h"
#include "physics/contact_lanes.h"
#include "physics/contact_schedule.h"
#include "physics_test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <span>
#include <string>
#include <vector>

namespace substep {
namespace {

/// ½ m v² + ½ ωᵀ I ω, I from the principal moments the body keeps.
double kinetic(const Body& b) {
    if (b.invMass == 0.0) return 0.0;
    const Vec3 omegaBody = b.q.conjugate() * b.omega;
    return 0.5 * b.mass * b.v.squaredNorm() + 0.5 * omegaBody.dot(b.inertia.cwiseProduct(omegaBody));
}

/// A random one-point pair: body 0 a sphere, body 1 a sphere (kind 0), a box (kind 1:
/// anisotropic inertia, the rest-frame path) or a static plane (kind 2), touching at body 0's
/// point along −n, with random orientations, masses and radii over two orders of magnitude.
/// The box's lever arm is anywhere in it, or along the normal (`boxLeverAlongNormal`).
struct RandomPair {
    Body bodies[2];
    ContactPair pair;
    Contact contact;
};

/// Eq. 27: where a body's point was before the substep.
Vec3 previousPointOf(const Body& b, const Vec3& local) { return b.xPrev + b.qPrev * local; }

RandomPair randomPair(std::mt19937& random, int kind, bool boxLeverAlongNormal = false) {
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    const auto logUniform = [&](double lo, double hi) { return lo * std::pow(hi / lo, 0.5 * (unit(random) + 1.0)); };
    const auto randomUnit = [&] { return Vec3(unit(random), unit(random), unit(random)).normalized(); };
    const auto randomTurn = [&] { return Quat(unit(random), unit(random), unit(random), unit(random)).normalized(); };
    RandomPair p;
    const double r0 = logUniform(0.02, 0.5);
    p.bodies[0] = makeBody({.shape = sphereShape(r0), .mass = logUniform(0.05, 20.0),
                            .position = Vec3(unit(random), unit(random), unit(random)),
                            .orientation = randomTurn()});
    const Vec3 n = randomUnit();  // from body 1 towards body 0
    const Vec3 point = p.bodies[0].x - r0 * n;
    if (kind == 0) {
        const double r1 = logUniform(0.02, 0.5);
        p.bodies[1] = makeBody({.shape = sphereShape(r1), .mass = logUniform(0.05, 20.0),
                                .position = point - r1 * n, .orientation = randomTurn()});
    } else if (kind == 1) {
        const Vec3 size(logUniform(0.05, 1.0), logUniform(0.05, 1.0), logUniform(0.05, 1.0));
        const Quat q = randomTurn();
        const Vec3 lever = boxLeverAlongNormal ? Vec3(q.conjugate() * (logUniform(0.02, 0.5) * -n))
                                               : Vec3(0.5 * size.cwiseProduct(Vec3(unit(random), unit(random), unit(random))));
        p.bodies[1] = makeBody({.shape = boxShape(size), .mass = logUniform(0.05, 20.0),
                                .position = point - q * lever, .orientation = q});
    } else {
        p.bodies[1] = makeBody({.shape = planeShape(n, n.dot(point)), .type = BodyType::Static});
    }
    for (Body& b : p.bodies) {
        b.xPrev = b.x;
        b.qPrev = b.q;
    }
    p.pair = {.body0 = 0, .body1 = 1, .count = 1};
    p.contact = {.local0 = p.bodies[0].q.conjugate() * (point - p.bodies[0].x),
                 .local1 = p.bodies[1].q.conjugate() * (point - p.bodies[1].x),
                 .normal = n};
    return p;
}

// The velocity pass of a point that pushed, with e = 0: Eq. 34 takes the normal velocity to
// 0 (ΔK = −v_n² / 2w), then Eq. 30's impulse j along the slip, at most |v_t| / w_t, gives
// ΔK = −j (|v_t| − j w_t / 2) ≤ 0. So the pair's kinetic energy never rises, whatever the
// velocities, masses, lever arms and the clamp (μ_d λ_n / h from far below to far above the
// slip). A form of either update that overshoots or turns the wrong way fails here.
TEST(ContactOnePointTest, VelocityPassNeverAddsKineticEnergy) {
    std::mt19937 random(11);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    const double h = test::kDt / 20.0;
    int clamped = 0, unclamped = 0;
    for (int trial = 0; trial < 6000; ++trial) {
        RandomPair p = randomPair(random, trial % 3);
        for (Body& b : p.bodies) {
            if (b.invMass == 0.0) continue;
            b.v = 2.0 * Vec3(unit(random), unit(random), unit(random));
            b.omega = 10.0 * Vec3(unit(random), unit(random), unit(random));
            b.vPrev = b.v;
            b.omegaPrev = b.omega;
        }
        p.pair.dynamicFriction = 0.5 * (unit(random) + 1.0);
        p.contact.lambdaNormal = std::pow(10.0, -9.0 + 6.0 * 0.5 * (unit(random) + 1.0));  // 1e-9 to 1e-3
        const double before = kinetic(p.bodies[0]) + kinetic(p.bodies[1]);
        solveContactVelocities(p.pair, std::span<const Contact>(&p.contact, 1), p.bodies, h, 10.0);
        const double after = kinetic(p.bodies[0]) + kinetic(p.bodies[1]);
        EXPECT_LE(after, before * (1.0 + 1e-12) + 1e-15) << "trial " << trial << ", kind " << trial % 3;
        // The normal velocity is 0 after the pass only when friction's coupling leaves it: it
        // is measured to count which side of the clamp the trials fell on.
        const Vec3 r0 = p.bodies[0].q * p.contact.local0;
        const Vec3 r1 = p.bodies[1].q * p.contact.local1;
        const Vec3 v = p.bodies[0].v + p.bodies[0].omega.cross(r0) - p.bodies[1].v - p.bodies[1].omega.cross(r1);
        const Vec3 slip = v - v.dot(p.contact.normal) * p.contact.normal;
        (slip.norm() < 1e-9 ? unclamped : clamped) += 1;
    }
    // Both sides of the clamp were visited (the slip removed whole, and cut short).
    EXPECT_GT(clamped, 1000);
    EXPECT_GT(unclamped, 200);
}

// Static friction (Eq. 27, Eq. 28 with α = 0) within μ_s λ_n: the correction is Δλ = |Δp_t| / w
// along −Δp_t (Eq. 4), so the point's motion along Δp_t over the substep, measured again on the
// corrected poses, is what the rotation's curvature leaves: of order |Δp_t|² / r, under 2 % of
// the slip for the slips here (1e-7 to 1e-3 m on levers of 0.02 m and more). Every lever arm
// lies along the normal, so the push does not turn the bodies and the slip friction sees is
// the one set up. Spheres and planes respond alike in every tangent direction, so there the
// whole tangential motion goes; an anisotropic box's scalar correction also moves the point
// across Δp_t (Eq. 4 is one direction's), so there only the motion along it is bounded. A
// correction scaled wrongly along the unnormalised slip, or applied to one body only, leaves a
// multiple of the slip.
TEST(ContactOnePointTest, StaticFrictionRemovesTheTangentialMotion) {
    std::mt19937 random(12);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    const double h = test::kDt / 20.0;
    SolverContext ctx{.h = h, .invH2 = 1.0 / (h * h)};
    int checked = 0;
    for (int trial = 0; trial < 6000; ++trial) {
        RandomPair p = randomPair(random, trial % 3, true);
        ctx.bodies = p.bodies;
        p.pair.staticFriction = 1e6;  // sticks: the bound is not what is tested here
        // This substep's motion: body 0 slid and turned from its start, and sank 1e-5 m into
        // body 1, so that the push acts first and friction then sees the slip.
        const Vec3 n = p.contact.normal;
        Vec3 slide = Vec3(unit(random), unit(random), unit(random));
        slide -= slide.dot(n) * n;
        const double slip = std::pow(10.0, -7.0 + 4.0 * 0.5 * (unit(random) + 1.0));
        Body& b0 = p.bodies[0];
        b0.xPrev = b0.x - slip * slide.normalized();
        b0.x -= 1e-5 * n;
        const Vec3 before = b0.x + b0.q * p.contact.local0 - previousPointOf(b0, p.contact.local0);
        solveContactPositions(p.pair, std::span<Contact>(&p.contact, 1), ctx);
        ASSERT_GT(p.contact.lambdaNormal, 0.0);
        const Body& b1 = p.bodies[1];
        const Vec3 motion = (b0.x + b0.q * p.contact.local0 - previousPointOf(b0, p.contact.local0)) -
                            (b1.x + b1.q * p.contact.local1 - previousPointOf(b1, p.contact.local1));
        const Vec3 left = motion - motion.dot(n) * n;
        const Vec3 slipBefore = before - before.dot(n) * n;
        const double measured = trial % 3 == 1 ? std::abs(left.dot(slipBefore.normalized())) : left.norm();
        EXPECT_LT(measured, 0.02 * slipBefore.norm() + 1e-12)
            << "trial " << trial << ", kind " << trial % 3 << ", slip " << slipBefore.norm();
        EXPECT_GT(p.pair.lambdaTangent1, 0.0);
        ++checked;
    }
    EXPECT_EQ(checked, 6000);
}

}  // namespace
}  // namespace substep

namespace substep {
namespace {

// solveTouchingPositions solves up to four one-point pairs at once, in vector lanes, where
// Gauss-Seidel's order allows (ContactSchedule: no moving body in common with one another or
// with the pairs they pass): the bodies and multipliers must come out bit for bit as solving the
// list in order one pair at a time. Few bodies and many pairs, so that most neighbours in the
// list share a body, a static plane and a static box shared by many, boxes (anisotropic) in some
// rounds, two-point patches among them that keep their place, pairs with a λ_t of two tangents
// left from a patch, and rounds of deep overlaps pushed out whole, whose turns go past the
// series of integrateRotation. Then the velocity pass the same way (solveTouchingVelocities
// against solveContactVelocities in order), on random velocities, with restitution, and with
// some points after the collision pass (removeApproach).
/// The check below, with the lanes in the instruction set chosen (contact_detail::useLaneIsa).
void expectLanesGiveTheBytesOfTheListedOrder() {
    std::mt19937 random(18);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    const auto randomTurn = [&] { return Quat(unit(random), unit(random), unit(random), unit(random)).normalized(); };
    for (int round = 0; round < 200; ++round) {
        const int bodyCount = 6 + round % 10;
        std::vector<Body> bodies;
        bodies.push_back(makeBody({.shape = planeShape(Vec3::UnitY(), -1.0), .type = BodyType::Static}));
        bodies.push_back(makeBody({.shape = boxShape(Vec3(2.0, 0.2, 2.0)), .type = BodyType::Static,
                                   .position = Vec3(0.0, 1.2, 0.0), .orientation = randomTurn()}));
        while (static_cast<int>(bodies.size()) < bodyCount) {
            bodies.push_back(makeBody({.shape = round % 3 == 0 ? boxShape(Vec3(0.1, 0.2, 0.3)) : sphereShape(0.1),
                                       .mass = 0.5 + unit(random) * 0.4,
                                       .position = Vec3(unit(random), unit(random), unit(random)),
                                       .orientation = randomTurn()}));
            Body& b = bodies.back();
            b.xPrev = b.x - 0.01 * Vec3(unit(random), unit(random), unit(random));
            b.qPrev = (b.q * Quat(1.0, 0.01 * unit(random), 0.01 * unit(random), 0.01 * unit(random))).normalized();
        }
        std::vector<ContactPair> pairs;
        std::vector<Contact> contacts;
        std::uniform_int_distribution<int> pick(0, bodyCount - 1);
        const int pairCount = 5 + round % 40;
        const bool deep = round % 5 == 4;  // pushed out whole (no cap): turns of over 0.2 rad
        while (static_cast<int>(pairs.size()) < pairCount) {
            const int i = pick(random), j = pick(random);
            if (i == j || (i < 2 && j < 2)) continue;
            const Body& b0 = bodies[i];
            const Body& b1 = bodies[j];
            const int points = round % 4 == 1 && pairs.size() % 5 == 2 ? 2 : 1;
            pairs.push_back({.body0 = static_cast<uint32_t>(i), .body1 = static_cast<uint32_t>(j),
                             .staticFriction = pairs.size() % 7 == 3 ? 0.0 : 0.6, .dynamicFriction = 0.4,
                             .restitution = pairs.size() % 3 == 1 ? 0.7 : 0.0,
                             .first = static_cast<uint32_t>(contacts.size()), .count = static_cast<uint32_t>(points),
                             .lambdaTangent1 = pairs.size() % 4 == 2 ? 1e-6 * unit(random) : 0.0,
                             .lambdaTangent2 = pairs.size() % 8 == 2 ? 1e-6 * unit(random) : 0.0,
                             .anchored = pairs.size() % 2 == 0});
            const Vec3 n = Vec3(unit(random), unit(random), unit(random)).normalized();
            for (int k = 0; k < points; ++k) {
                // Overlapping by up to 5 mm (some not at all), anywhere between the bodies.
                const Vec3 centre = 0.5 * (b0.x + b1.x) + 0.05 * Vec3(unit(random), unit(random), unit(random));
                const double depth = (deep ? 0.3 : 0.005) * unit(random);
                const Vec3 p0 = centre - 0.5 * depth * n, p1 = centre + 0.5 * depth * n;
                contacts.push_back({.local0 = b0.q.conjugate() * (p0 - b0.x),
                                    .local1 = b1.q.conjugate() * (p1 - b1.x),
                                    .normal = n});
            }
        }
        std::vector<uint32_t> touching(pairs.size());
        for (uint32_t p = 0; p < touching.size(); ++p) touching[p] = p;

        std::vector<Body> inOrderBodies = bodies;
        std::vector<ContactPair> inOrderPairs = pairs;
        std::vector<Contact> inOrderContacts = contacts;
        const double h = 1.0 / 1200.0;
        SolverContext inOrder{.bodies = inOrderBodies.data(), .h = h, .invH2 = 1.0 / (h * h), .capPushOut = !deep};
        for (const uint32_t p : touching)
            solveContactPositions(inOrderPairs[p], std::span(inOrderContacts).subspan(inOrderPairs[p].first, inOrderPairs[p].count),
                                  inOrder);
        SolverContext inLanes{.bodies = bodies.data(), .h = h, .invH2 = 1.0 / (h * h), .capPushOut = !deep};
        ContactSchedule schedule;
        schedule.plan(touching, pairs, bodies);
        solveTouchingPositions(schedule, pairs, contacts, inLanes);

        for (size_t b = 0; b < bodies.size(); ++b) {
            for (int k = 0; k < 3; ++k) ASSERT_EQ(bodies[b].x[k], inOrderBodies[b].x[k]) << "round " << round << " body " << b;
            for (int k = 0; k < 4; ++k)
                ASSERT_EQ(bodies[b].q.coeffs()[k], inOrderBodies[b].q.coeffs()[k]) << "round " << round << " body " << b;
        }
        for (size_t p = 0; p < pairs.size(); ++p) {
            ASSERT_EQ(pairs[p].lambdaNormal, inOrderPairs[p].lambdaNormal) << "round " << round << " pair " << p;
            ASSERT_EQ(pairs[p].lambdaTangent1, inOrderPairs[p].lambdaTangent1) << "round " << round << " pair " << p;
            ASSERT_EQ(pairs[p].lambdaTangent2, inOrderPairs[p].lambdaTangent2) << "round " << round << " pair " << p;
            ASSERT_EQ(pairs[p].anchored, inOrderPairs[p].anchored) << "round " << round << " pair " << p;
        }
        for (size_t i = 0; i < contacts.size(); ++i)
            ASSERT_EQ(contacts[i].lambdaNormal, inOrderContacts[i].lambdaNormal) << "round " << round << " point " << i;

        // The velocity pass: the same random velocities on both copies, a point in five after
        // the collision pass (half of those with a collision impulse).
        for (size_t b = 2; b < bodies.size(); ++b) {
            Body& body = bodies[b];
            body.v = Vec3(unit(random), unit(random), unit(random));
            body.omega = 3.0 * Vec3(unit(random), unit(random), unit(random));
            body.vPrev = body.v + 0.2 * Vec3(unit(random), unit(random), unit(random));
            body.omegaPrev = body.omega + 0.5 * Vec3(unit(random), unit(random), unit(random));
            Body& copy = inOrderBodies[b];
            copy.v = body.v, copy.omega = body.omega, copy.vPrev = body.vPrev, copy.omegaPrev = body.omegaPrev;
        }
        for (size_t i = 0; i < contacts.size(); ++i) {
            if (i % 5 != 4) continue;
            contacts[i].collisionPass = inOrderContacts[i].collisionPass = true;
            contacts[i].restitutionImpulse = inOrderContacts[i].restitutionImpulse = i % 10 == 4 ? 0.3 : 0.0;
        }
        for (const uint32_t p : touching)
            solveContactVelocities(inOrderPairs[p],
                                   std::span<const Contact>(inOrderContacts).subspan(inOrderPairs[p].first, inOrderPairs[p].count),
                                   inOrderBodies.data(), h, 10.0);
        solveTouchingVelocities(schedule, pairs, contacts, bodies.data(), h, 10.0);
        for (size_t b = 0; b < bodies.size(); ++b)
            for (int k = 0; k < 3; ++k) {
                ASSERT_EQ(bodies[b].v[k], inOrderBodies[b].v[k]) << "round " << round << " body " << b;
                ASSERT_EQ(bodies[b].omega[k], inOrderBodies[b].omega[k]) << "round " << round << " body " << b;
            }
    }
}

// The schedule looks for a one-point pair's partners well past its next few pairs: in a pile,
// sorted by first body, the next pairs mostly share a body with it (a window of eight filled
// spheres1000's steps with 2.9 pairs on average, against 3.95 at 32). Pair 0 is followed by
// twelve pairs on its first body, each also blocking a body of its own; three independent pairs
// come after them, and join pair 0's step; the twelve keep their places, one step each.
TEST(ContactScheduleTest, PartnersComeFromPastTheNextEightPairs) {
    std::vector<Body> bodies;
    bodies.push_back(makeBody({.shape = planeShape(Vec3::UnitY(), 0.0), .type = BodyType::Static}));
    for (int i = 1; i < 30; ++i)
        bodies.push_back(makeBody({.shape = sphereShape(0.1), .position = Vec3(0.3 * i, 0.1, 0.0)}));
    std::vector<ContactPair> pairs;
    const auto add = [&](uint32_t body0, uint32_t body1) {
        pairs.push_back({.body0 = body0, .body1 = body1, .first = static_cast<uint32_t>(pairs.size()), .count = 1});
    };
    add(1, 2);
    for (uint32_t other = 3; other < 15; ++other) add(1, other);
    add(20, 21);
    add(0, 22);  // the static plane blocks nothing
    add(24, 25);
    std::vector<uint32_t> touching(pairs.size());
    for (uint32_t p = 0; p < touching.size(); ++p) touching[p] = p;
    ContactSchedule schedule;
    schedule.plan(touching, pairs, bodies);
    const std::span<const uint32_t> steps = schedule.steps();
    ASSERT_GE(steps.size(), 5u);
    EXPECT_EQ(steps[0], 4u);
    EXPECT_EQ(std::vector<uint32_t>(steps.begin() + 1, steps.begin() + 5), (std::vector<uint32_t>{0, 13, 14, 15}));
    // Then the twelve, alone and in order.
    ASSERT_EQ(steps.size(), 5u + 2 * 12);
    for (uint32_t k = 0; k < 12; ++k) {
        EXPECT_EQ(steps[5 + 2 * k], 1u);
        EXPECT_EQ(steps[6 + 2 * k], 1 + k);
    }
}

// A schedule keeps its steps while the listed pairs and what it read of them stay the same
// (a pile's touching pairs mostly do, substep to substep). Whatever changed since its last plan,
// a pair's point count, a body's mass, the bodies of the pair at an index (a new frame's pairs)
// or the list, it plans again: its steps are those a new schedule plans.
TEST(ContactScheduleTest, PlansAgainWhatChangedSinceItsLastPlan) {
    std::vector<Body> bodies;
    for (int i = 0; i < 12; ++i)
        bodies.push_back(makeBody({.shape = sphereShape(0.1), .position = Vec3(0.3 * i, 0.1, 0.0)}));
    std::vector<ContactPair> pairs;
    for (uint32_t b = 0; b < 12; b += 2)  // six pairs of their own bodies: steps of 4 and 2
        pairs.push_back({.body0 = b, .body1 = b + 1, .first = b / 2, .count = 1});
    std::vector<uint32_t> touching(pairs.size());
    for (uint32_t p = 0; p < touching.size(); ++p) touching[p] = p;
    ContactSchedule kept;
    const auto expectStepsOfANewPlan = [&](const char* what) {
        SCOPED_TRACE(what);
        kept.plan(touching, pairs, bodies);
        ContactSchedule fresh;
        fresh.plan(touching, pairs, bodies);
        const std::span<const uint32_t> keptSteps = kept.steps();
        const std::span<const uint32_t> freshSteps = fresh.steps();
        EXPECT_EQ(std::vector<uint32_t>(keptSteps.begin(), keptSteps.end()),
                  std::vector<uint32_t>(freshSteps.begin(), freshSteps.end()));
        EXPECT_EQ(std::vector<uint32_t>(kept.touching().begin(), kept.touching().end()), touching);
    };
    expectStepsOfANewPlan("first plan");
    ASSERT_EQ(kept.steps()[0], 4u);
    expectStepsOfANewPlan("nothing changed");
    // Each change below changes the steps.
    pairs[1].count = 2;  // a patch leaves the lanes: {0, 2, 3, 4}, {1}, {5}
    expectStepsOfANewPlan("a pair's point count");
    pairs[2] = {.body0 = 1, .body1 = 8, .first = 2, .count = 1};  // shares body 1 with pair 0
    expectStepsOfANewPlan("the bodies of a pair");
    bodies[1] = makeBody({.shape = sphereShape(0.1), .type = BodyType::Static});  // blocks nothing
    expectStepsOfANewPlan("a body's mass");
    touching.erase(touching.begin() + 3);
    expectStepsOfANewPlan("a pair gone from the list");
    touching.clear();
    expectStepsOfANewPlan("no pair");
}

TEST(ContactOnePointTest, TouchingPairsSolvedInLanesGiveTheBytesOfTheListedOrder) {
    using contact_detail::LaneIsa;
    // Every instruction set the lanes are compiled for that this CPU runs (the base one always).
    for (const LaneIsa isa : {LaneIsa::Base, LaneIsa::Avx2, LaneIsa::Avx512}) {
        if (isa > contact_detail::widestLaneIsa()) continue;
        SCOPED_TRACE("lane instruction set " + std::to_string(static_cast<int>(isa)));
        const LaneIsa before = contact_detail::useLaneIsa(isa);
        expectLanesGiveTheBytesOfTheListedOrder();
        contact_detail::useLaneIsa(before);
    }
}

}  // namespace
}  // namespace substep
