// Tests engine/physics/contact_turn.h: turnBy against the exact turn (the exponential map, an
// angle-axis quaternion) and against integrateRotation, which it stands in for.

#include "physics/contact_turn.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace substep {
namespace {

Quat exactTurn(const Quat& q, const Vec3& rotation) {
    const double angle = rotation.norm();
    if (angle == 0.0) return q;
    return Quat(Eigen::AngleAxisd(angle, rotation / angle)) * q;
}

double largestDifference(const Quat& a, const Quat& b) {
    return (a.coeffs() - b.coeffs()).cwiseAbs().maxCoeff();
}

// Small turns (|θ| from 1e-12 to just under 0.02 rad, the short path's range) of random unit
// orientations land on the exact turn to a few roundings, with |q| = 1 to rounding.
TEST(ContactTurnTest, SmallTurnsAreExactToRounding) {
    std::mt19937 random(7);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    for (int trial = 0; trial < 20000; ++trial) {
        const Quat q = Quat(unit(random), unit(random), unit(random), unit(random)).normalized();
        const Vec3 axis = Vec3(unit(random), unit(random), unit(random)).normalized();
        const double angle = 0.0199 * std::pow(10.0, -10.0 * std::abs(unit(random)));
        const Vec3 rotation = angle * axis;
        Quat turned = q;
        turnBy(turned, rotation);
        EXPECT_LT(largestDifference(turned, exactTurn(q, rotation)), 1e-15) << angle;
        EXPECT_LT(std::abs(turned.norm() - 1.0), 1e-15) << angle;
    }
}

// Beyond the short path's range, and for a quaternion that is not unit, turnBy is
// integrateRotation bit for bit.
TEST(ContactTurnTest, LargeTurnsAndNonUnitQuaternionsTakeTheGeneralPath) {
    const Quat q = Quat(0.3, -0.5, 0.2, 0.7).normalized();
    for (const double angle : {0.021, 0.3, 2.0, 4.0}) {
        const Vec3 rotation = angle * Vec3(1.0, 2.0, -2.0).normalized();
        Quat viaTurn = q;
        Quat viaIntegrate = q;
        turnBy(viaTurn, rotation);
        integrateRotation(viaIntegrate, rotation);
        EXPECT_EQ(viaTurn.coeffs(), viaIntegrate.coeffs()) << angle;
    }
    const Quat notUnit(q.coeffs() * (1.0 + 1e-6));
    Quat viaTurn = notUnit;
    Quat viaIntegrate = notUnit;
    turnBy(viaTurn, Vec3(1e-3, 0.0, 0.0));
    integrateRotation(viaIntegrate, Vec3(1e-3, 0.0, 0.0));
    EXPECT_EQ(viaTurn.coeffs(), viaIntegrate.coeffs());
}

// A million turns about one axis add up to the one turn by their sum, and |q| does not drift:
// the factor that replaces the renormalisation corrects what rounding leaves.
TEST(ContactTurnTest, ManyTurnsAddUpWithoutDrift) {
    const Quat start = Quat(0.9, 0.1, -0.3, 0.2).normalized();
    const Vec3 axis = Vec3(-1.0, 3.0, 0.5).normalized();
    const double step = 3e-6;
    const int turns = 1000000;
    Quat q = start;
    double largestDrift = 0.0;
    for (int i = 0; i < turns; ++i) {
        turnBy(q, step * axis);
        largestDrift = std::max(largestDrift, std::abs(q.norm() - 1.0));
    }
    EXPECT_LT(largestDrift, 1e-15);
    EXPECT_LT(largestDifference(q, exactTurn(start, (step * turns) * axis)), 1e-10);
}

}  // namespace
}  // namespace substep
