// Tests engine/physics/contact_restitution.cpp (and the single-point velocity pass of
// contact.cpp that uses it): an impact passes through a row of spheres as the closed forms of
// elastic and inelastic two-body collisions say, whatever order the bodies are listed in,
// touching or with gaps, floating or resting on a frictionless floor, equal or unequal masses.

#include "physics/world.h"

#include "physics_test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
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

/// Listing orders to try: every permutation up to five bodies, otherwise the row's order, its
/// reverse and a fixed set of shuffles.
std::vector<std::vector<size_t>> orders(size_t n) {
    std::vector<size_t> order(n);
    std::iota(order.begin(), order.end(), 0);
    std::vector<std::vector<size_t>> result;
    if (n <= 5) {
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

}  // namespace
}  // namespace substep
