// Tests the contact solve (engine/physics/contact.cpp) against curved geometry, the paper's
// point (section 3.5, Fig. 14): the current normal at every substep keeps a marble on a curve.

#include "physics/collision/spline_tube.h"
#include "physics_test_support.h"

#include <gtest/gtest.h>

#include <cmath>

namespace substep {
namespace {

/// A marble running at 5 m/s inside a hollow ring of radius 1 m (a pipe bent into a circle)
/// stays inside it: the centripetal acceleration v²/R = 25 m/s² comes from the tube wall
/// alone, re-aimed every substep.
TEST(CurvedContactTest, MarbleStaysInsideACurvedTubeAt5MetresPerSecond) {
    constexpr double kRing = 1.0;
    constexpr double kTube = 0.05;
    constexpr double kMarble = 0.02;
    std::vector<Vec3> ring;
    for (int i = 0; i < 24; ++i) {
        const double a = 2.0 * test::kPi * i / 24;
        ring.emplace_back(kRing * std::cos(a), 0.0, kRing * std::sin(a));
    }
    World world({.gravity = Vec3(0, -10, 0), .substeps = 20});
    world.createBody({.shape = splineShape(makeSplineTube(ring, kTube, true, true)),
                      .type = BodyType::Static,
                      .staticFriction = 0.0,
                      .dynamicFriction = 0.0});
    const BodyId marble = world.createBody({.shape = sphereShape(kMarble),
                                            .mass = 0.01,
                                            .position = Vec3(kRing, -(kTube - kMarble), 0.0),
                                            .velocity = Vec3(0.0, 0.0, 5.0),
                                            .staticFriction = 0.0,
                                            .dynamicFriction = 0.0});
    double farthest = 0.0;
    double slowest = 5.0;
    test::runFor(world, 2.0, [&](double) {
        const Body& b = world.body(marble);
        const Vec3 radial(b.x.x(), 0.0, b.x.z());
        const double offCentre = std::hypot(radial.norm() - kRing, b.x.y());
        farthest = std::max(farthest, offCentre);
        slowest = std::min(slowest, b.v.norm());
    });
    ASSERT_TRUE(world.isFinite());
    // Inside the pipe: the centre never strays beyond the wall by more than a millimetre.
    EXPECT_LT(farthest, kTube - kMarble + 1e-3);
    // Frictionless: it keeps running around the ring (it went round about 1.6 times).
    EXPECT_GT(slowest, 4.5);
}

/// A marble on a two-wire track (Fig. 13's) rolls down it on the wires: it turns about the line
/// through its two contact points, at the height ρ below its centre, so it accelerates at
/// a = g sin θ / (1 + I / (m ρ²)), I = 2/5 m r², slower than on a plane (5/7 g sin θ).
TEST(CurvedContactTest, MarbleRidesATwoWireTrack) {
    World world({.gravity = Vec3(0, -10, 0), .substeps = 20});
    constexpr double kWire = 0.005;
    constexpr double kMarble = 0.03;
    constexpr double kGap = 0.04;  // wires 4 cm apart
    for (double side : {-0.5, 0.5}) {
        std::vector<Vec3> wire;
        for (int i = 0; i <= 20; ++i) wire.emplace_back(0.2 * i - 2.0, -0.05 * 0.2 * i, side * kGap);
        world.createBody({.shape = splineShape(makeSplineTube(wire, kWire, false, false)),
                          .type = BodyType::Static});
    }
    // Resting height above the wires: the marble touches both at half the gap sideways.
    const double rise = std::sqrt(std::pow(kMarble + kWire, 2) - std::pow(0.5 * kGap, 2));
    const BodyId marble = world.createBody(
        {.shape = sphereShape(kMarble), .mass = 0.02, .position = Vec3(-1.9, -0.005 + rise, 0.0)});
    constexpr double kSeconds = 1.5;
    test::runFor(world, kSeconds, [](double) {});
    const Body& b = world.body(marble);
    ASSERT_TRUE(world.isFinite());
    const double slope = 0.05;
    const double sine = slope / std::sqrt(1.0 + slope * slope);
    const double rho = rise * kMarble / (kMarble + kWire);  // contacts lie on the centre lines
    const double inertiaRatio = 0.4 * kMarble * kMarble / (rho * rho);
    const double acceleration = 10.0 * sine / (1.0 + inertiaRatio);
    const double travelled = (b.x.x() + 1.9) * std::sqrt(1.0 + slope * slope);
    EXPECT_NEAR(travelled, 0.5 * acceleration * kSeconds * kSeconds, 0.02 * travelled);
    EXPECT_NEAR(b.x.z(), 0.0, 2e-3);               // between the wires
    const double wireHeight = -0.05 * (b.x.x() + 2.0);
    EXPECT_NEAR(b.x.y() - wireHeight, rise, 2e-3);  // on them, neither through nor above
}

}  // namespace
}  // namespace substep
