// Stability of fast spins (docs/STABILITY.md): free bodies, a wheel on a hinge spinning about the
// hinge axis (held by the world and by a light carrier), an unbalanced bar whirled about a
// hinge, and a spinning top on a spherical joint, at 100 and 1000 rad/s.

#include "stability_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace substep::stability {
namespace {

constexpr double kWheelMass = 0.76;
const Vec3 kWheelSize(0.15, 0.15, 0.05);  // a disc-like box, axle along z: I_z = 1.8 I_x
const Vec3 kPivot(0.0, 1.0, 0.0);
const std::vector<int> kCounts{1, 2, 5, 10, 20, 40, 80, 160, 320};

std::string rateTag(double rate) {
    return std::to_string(static_cast<int>(rate));
}

std::string rateName(const ::testing::TestParamInfo<double>& param) {
    return "At" + rateTag(param.param);
}

/// Runs `world` for `seconds` and measures the largest relative change of `rate()` from `rate0`.
template <class Rate>
Outcome watchRate(World& world, double seconds, double rate0, Rate&& rate) {
    return watch(world, seconds, kDt,
                 [&](double) { return std::abs(rate() - rate0) / std::abs(rate0); });
}

/// Holds for a spin: finite, no energy gained beyond 0.5 % of the kinetic energy at the start,
/// the rate within 1 %.
Bounds spinBounds(double kinetic) {
    return {.energyGain = 0.005 * kinetic, .measure = 0.01};
}

// --- Free bodies ------------------------------------------------------------------------------

// A free ball (equal moments: no gyroscopic term) and a free disc spinning exactly about its axle
// (ω × Iω = 0) keep their rate to rounding at every count from which a substep turns by less than
// π: at 1000 rad/s and 1 substep a frame turns by 16.7 rad, which the velocity derivation reads
// back as an angle in (−π, π] (188 rad/s at 1 substep; the rate cannot be represented below
// about ω dt / π = 5.3 substeps). No gravity, 2 s.
class FreeSpinTest : public ::testing::TestWithParam<double> {};

TEST_P(FreeSpinTest, BallAndDiscAboutTheAxleKeepRateAndEnergy) {
    const double rate = GetParam();
    for (const bool disc : {false, true}) {
        const std::string name = std::string(disc ? "free_disc_" : "free_ball_") + rateTag(rate);
        const double radius = 0.075;
        const double moment = disc ? test::boxMoments(kWheelSize, kWheelMass).z()
                                   : 0.4 * kWheelMass * radius * radius;
        const Bounds bounds = spinBounds(0.5 * moment * rate * rate);
        const Sweep sweep = sweepSubsteps(name, kCounts, bounds, [&](int substeps) {
            World world(WorldSettings{.gravity = Vec3::Zero(), .substeps = substeps});
            const BodyId id =
                world.createBody({.shape = disc ? boxShape(kWheelSize) : sphereShape(radius),
                                  .mass = kWheelMass,
                                  .angularVelocity = Vec3(0, 0, rate)});
            return watchRate(world, 2.0, rate, [&] { return world.body(id).omega.z(); });
        });
        // Holds from the first count that turns by less than π per substep.
        expectStable(name, sweep, 0.5 * moment * rate * rate, rate > 500.0 ? 10 : 1);
    }
}

INSTANTIATE_TEST_SUITE_P(Rates, FreeSpinTest, ::testing::Values(100.0, 1000.0), rateName);

// A free disc spinning about its axle (the largest moment: a stable spin) with a 1 % wobble
// (ω_x = 0.01 ω). The exact motion keeps energy and |L|; ω precesses about L at about
// λ = 0.8 ω in the body. FIXED weak spot (docs/STABILITY.md): the explicit gyroscopic term of
// Algorithm 2 grew the wobble as exp(λ² h t / 2) (100 rad/s held only from 80 substeps, 1000 rad/s
// gained 2000 times its energy at 320). With the implicit term (one Newton step) the disc gains
// nothing and keeps |L| within 2e-5 at every count where a substep turns by less than π: 100
// rad/s holds from 1 substep, 1000 rad/s from 10. Asserted tightly: it fails if that regresses.
class WobblingDiscTest : public ::testing::TestWithParam<double> {};

TEST_P(WobblingDiscTest, MajorAxisSpinWithAWobble) {
    const double rate = GetParam();
    const std::string name = "free_disc_wobble_" + rateTag(rate);
    const Vec3 moments = test::boxMoments(kWheelSize, kWheelMass);
    const Vec3 omega0(0.01 * rate, 0.0, rate);
    const double kinetic = 0.5 * omega0.dot(moments.cwiseProduct(omega0));
    const double l0 = moments.cwiseProduct(omega0).norm();
    const Bounds bounds = spinBounds(kinetic);
    const Sweep sweep = sweepSubsteps(name, kCounts, bounds, [&](int substeps) {
        World world(WorldSettings{.gravity = Vec3::Zero(), .substeps = substeps});
        const BodyId id = world.createBody(
            {.shape = boxShape(kWheelSize), .mass = kWheelMass, .angularVelocity = omega0});
        // The measure: the relative change of |L| (conserved without torque).
        return watch(world, 2.0, kDt, [&](double) {
            return std::abs(test::angularMomentum(world.body(id), moments).norm() - l0) / l0;
        });
    });
    report(name + "_energy_gain_over_kinetic_at_20", sweep.at(20).energyGain / kinetic);
    EXPECT_LE(sweep.at(20).energyGain, 1e-6 * kinetic) << name << " @ 20 substeps gains energy";
    expectStable(name, sweep, kinetic, rate > 500.0 ? 10 : 1);
}

INSTANTIATE_TEST_SUITE_P(Rates, WobblingDiscTest, ::testing::Values(100.0, 1000.0), rateName);

// --- A wheel on a hinge -----------------------------------------------------------------------

/// A disc wheel on a hinge about its axle (z), under gravity, spinning at `rate`: either hinged
/// to the world directly or to a light carrier (30 g, 1:25) welded to the world, the way a
/// wheel sits on a steering knuckle.
struct HingedWheel {
    World world;
    BodyId wheel;

    HingedWheel(int substeps, double rate, bool carrier)
        : world(WorldSettings{.gravity = Vec3(0, -kG, 0), .substeps = substeps}) {
        BodyId holder;
        if (carrier) {
            holder = world.createBody(
                {.shape = boxShape(Vec3(0.03, 0.02, 0.02)), .mass = 0.03, .position = kPivot});
            world.createJoint({.type = JointType::Fixed, .body1 = holder, .anchor0 = kPivot});
        }
        const Vec3 axle(0, 0, 0.06);
        wheel = world.createBody({.shape = boxShape(kWheelSize),
                                  .mass = kWheelMass,
                                  .position = kPivot + axle,
                                  .angularVelocity = Vec3(0, 0, rate)});
        world.createJoint({.type = JointType::Hinge,
                           .body0 = holder,
                           .body1 = wheel,
                           .anchor0 = carrier ? axle : Vec3(kPivot + axle),
                           .axis0 = Vec3::UnitZ(),
                           .axis1 = Vec3::UnitZ()});
    }

    double spin() const {
        const Body& w = world.body(wheel);
        return w.omega.dot(test::userAxis(w, Vec3::UnitZ()));
    }
};

// Held by the world, the hinge removes every off-axis rotation exactly each substep, so nothing
// can grow: the rate and energy are kept to rounding. Held by a light carrier welded to the world,
// the hinge's alignment moves mostly the carrier, the weld moves it back, and the wheel keeps a
// small tilt every substep; with its spin that is the wobble of WobblingDiscTest. FIXED weak spot
// (docs/STABILITY.md): the explicit gyroscopic term pumped it (1000 rad/s: 7 times its 1.4 kJ at
// 20 substeps, 1e12 J at 160, holding only at 320); with the implicit term the wheel on the
// carrier gains nothing at any count and holds from 1 substep at 100 rad/s and from 10 (π per
// substep) at 1000 rad/s, as the wheel held by the world. Gravity on, 2 s.
class HingedWheelTest : public ::testing::TestWithParam<double> {};

TEST_P(HingedWheelTest, WheelSpinsAboutItsHingeAxis) {
    const double rate = GetParam();
    for (const bool carrier : {false, true}) {
        const std::string name =
            std::string(carrier ? "hinged_wheel_on_carrier_" : "hinged_wheel_") + rateTag(rate);
        const Vec3 moments = test::boxMoments(kWheelSize, kWheelMass);
        const Bounds bounds = spinBounds(0.5 * moments.z() * rate * rate);
        const Sweep sweep = sweepSubsteps(name, kCounts, bounds, [&](int substeps) {
            HingedWheel rig(substeps, rate, carrier);
            return watchRate(rig.world, 2.0, rate, [&] { return rig.spin(); });
        });
        // Held by the world or by the carrier, it holds wherever a substep turns by less than π.
        const int documented = rate > 500.0 ? 10 : 1;
        expectStable(name, sweep, 0.5 * moments.z() * rate * rate, documented);
    }
}

INSTANTIATE_TEST_SUITE_P(Rates, HingedWheelTest, ::testing::Values(100.0, 1000.0), rateName);

// A 0.2 m bar (0.5 kg) whirled about a hinge at one end, in the horizontal plane, without
// gravity: the hinge supplies the centripetal force m ω² L/2 (1 kN at 100 rad/s, 100 kN at 1000).
// The rate is NOT kept: each substep the bar moves along the tangent and the attachment pulls it
// back along the radius, and the velocity derived from that chord is short by about (ωh)²
// (a point mass on a circle loses 3/8 (ωh)² per substep). This is ERRATA item 8's step-size
// damping, growing as ω³: measured, dω/dt = −c h ω³ with c = 0.75, i.e.
// 1/ω² = 1/ω0² + 1.5 h t, at every count and both rates (100 rad/s falls to 20 rad/s in 2 s at 20
// substeps, 1000 rad/s to the same 20 rad/s). Holds: finite, no energy gained beyond 0.5 % of
// the kinetic energy, joint error < 1 mm, and the rate within 10 % of that law.
class WhirledBarTest : public ::testing::TestWithParam<double> {};

TEST_P(WhirledBarTest, BarWhirledAboutAHingeSlowsByTheDampingLaw) {
    const double rate = GetParam();
    const std::string name = "whirled_bar_" + rateTag(rate);
    const double length = 0.2, mass = 0.5;
    const Vec3 size(length, 0.02, 0.02);
    const double pivotInertia = test::boxMoments(size, mass).z() + mass * length * length / 4;
    const Bounds bounds{
        .energyGain = 0.005 * 0.5 * pivotInertia * rate * rate, .jointError = 1e-3, .measure = 0.1};
    double lossAt20 = 0.0;
    const Sweep sweep = sweepSubsteps(name, kCounts, bounds, [&](int substeps) {
        World world(WorldSettings{.gravity = Vec3::Zero(), .substeps = substeps});
        const BodyId bar = world.createBody({.shape = boxShape(size),
                                             .mass = mass,
                                             .position = kPivot + Vec3(length / 2, 0, 0),
                                             .velocity = Vec3(0, rate * length / 2, 0),
                                             .angularVelocity = Vec3(0, 0, rate)});
        world.createJoint({.type = JointType::Hinge,
                           .body1 = bar,
                           .anchor0 = kPivot,
                           .anchor1 = Vec3(-length / 2, 0, 0),
                           .axis0 = Vec3::UnitZ(),
                           .axis1 = Vec3::UnitZ()});
        const double h = kDt / substeps;
        const Outcome o = watch(world, 2.0, kDt, [&](double t) {
            const double law = 1.0 / std::sqrt(1.0 / (rate * rate) + 1.5 * h * t);
            return std::abs(world.body(bar).omega.z() - law) / law;
        });
        if (substeps == 20) lossAt20 = 1.0 - world.body(bar).omega.z() / rate;
        return o;
    });
    report(name + "_rate_lost_in_2s_at_20", lossAt20);
    for (const Outcome& o : sweep.outcomes)
        EXPECT_LE(o.energyGain, bounds.energyGain);
    expectStable(name, sweep, 0.5 * pivotInertia * rate * rate, rate > 500.0 ? 20 : 5);
}

INSTANTIATE_TEST_SUITE_P(Rates, WhirledBarTest, ::testing::Values(100.0, 1000.0), rateName);

// --- A spinning top on a spherical joint --------------------------------------------------------

// The disc spins about its axle, tilted 30° from the vertical, on a spherical joint 5 cm below its
// centre on the axle: a top that precesses under gravity (slowly: Ω = m g d / (I_z ω)) and keeps
// its energy. The pivot's projection damps the nutation faster than the explicit gyroscopic term
// pumps it: measured, it holds from 5 substeps at 100 rad/s (2 substeps read a 1.5 % spin change)
// and wherever a substep turns by less than π at 1000. Holds: finite, energy gain < 0.5 % of the
// spin energy, spin within 1 %, joint error < 1 mm.
class SpinningTopTest : public ::testing::TestWithParam<double> {};

TEST_P(SpinningTopTest, TopPrecessesOnASphericalJoint) {
    const double rate = GetParam();
    const std::string name = "spinning_top_" + rateTag(rate);
    const Vec3 moments = test::boxMoments(kWheelSize, kWheelMass);
    Bounds bounds = spinBounds(0.5 * moments.z() * rate * rate);
    bounds.jointError = 1e-3;
    const Quat tilt(Eigen::AngleAxisd(kPi / 6, Vec3::UnitX()));
    // The disc's axle (user z) turned from vertical (world y) by 30°.
    const Quat orientation = tilt * Quat::FromTwoVectors(Vec3::UnitZ(), Vec3::UnitY());
    const Vec3 axle = orientation * Vec3::UnitZ();
    const Sweep sweep = sweepSubsteps(name, kCounts, bounds, [&](int substeps) {
        World world(WorldSettings{.gravity = Vec3(0, -kG, 0), .substeps = substeps});
        const BodyId top = world.createBody({.shape = boxShape(kWheelSize),
                                             .mass = kWheelMass,
                                             .position = kPivot + 0.05 * axle,
                                             .orientation = orientation,
                                             .angularVelocity = rate * axle});
        world.createJoint({.type = JointType::Spherical,
                           .body1 = top,
                           .anchor0 = kPivot,
                           .anchor1 = Vec3(0, 0, -0.05)});
        return watchRate(world, 2.0, rate, [&] {
            const Body& b = world.body(top);
            return b.omega.dot(test::userAxis(b, Vec3::UnitZ()));
        });
    });
    expectStable(name, sweep, 0.5 * moments.z() * rate * rate, rate > 500.0 ? 10 : 5);
}

INSTANTIATE_TEST_SUITE_P(Rates, SpinningTopTest, ::testing::Values(100.0, 1000.0), rateName);

}  // namespace
}  // namespace substep::stability
