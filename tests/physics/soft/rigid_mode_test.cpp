// Tests engine/physics/soft/rigid_mode.h: a particle set's moments against the closed forms of
// point masses, and the momentum-keeping spin against its defining equation Rot(h ω) I ω = L.
#include "physics/soft/rigid_mode.h"

#include <gtest/gtest.h>

#include <vector>

namespace substep {
namespace {

TEST(RigidMode, MomentsOfABoxsCornersFarFromTheOrigin) {
    // Eight particles of mass m at (±a, ±b, ±c) from a centre 1 km away, moving rigidly:
    // I = 8 m diag(b² + c², a² + c², a² + b²), L = I ω, momentum 8 m v.
    const double m = 0.7, a = 0.1, b = 0.2, c = 0.3;
    const Vec3 centre(1000.0, -400.0, 250.0), velocity(1, -2, 0.5), omega(0.3, -4.0, 2.0);
    std::vector<Vec3> x, v;
    std::vector<double> masses(8, m);
    for (int n = 0; n < 8; ++n) {
        const Vec3 r((n & 1 ? a : -a), (n & 2 ? b : -b), (n & 4 ? c : -c));
        x.push_back(centre + r);
        v.push_back(velocity + omega.cross(r));
    }
    const RigidModeMoments moments = rigidModeMoments(x.data(), v.data(), masses.data(), 8);
    const Mat3 inertia =
        8 * m * Vec3(b * b + c * c, a * a + c * c, a * a + b * b).asDiagonal().toDenseMatrix();
    EXPECT_NEAR(moments.mass, 8 * m, 1e-15);
    EXPECT_LT((moments.centre - centre).norm(), 1e-12);
    EXPECT_LT((moments.velocity - velocity).norm(), 1e-14);
    EXPECT_LT((moments.inertia - inertia).norm(), 1e-9 * inertia.norm());  // summed 1 km out
    EXPECT_LT((moments.angularMomentum - inertia * omega).norm(), 1e-9 * (inertia * omega).norm());
}

TEST(RigidMode, TheSpinKeepsTheAngularMomentumThroughTheTurn) {
    // An anisotropic inertia at a general orientation: after turning by h ω the inertia is
    // Rot I Rotᵀ and the angular momentum Rot I ω, which must still be L.
    const Mat3 turn = Quat(Eigen::AngleAxisd(0.8, Vec3(1, 2, -1).normalized())).toRotationMatrix();
    const Mat3 inertia = turn * Vec3(0.5, 2.0, 3.5).asDiagonal() * turn.transpose();
    const Vec3 angularMomentum(3.0, -1.0, 7.0);
    for (const double h : {1e-4, 1e-3, 1e-2}) {
        const Vec3 omega = momentumKeepingSpin(inertia, angularMomentum, h);
        Quat rotation = Quat::Identity();
        integrateRotation(rotation, h * omega);
        const Vec3 after = rotation * Vec3(inertia * omega);
        EXPECT_LT((after - angularMomentum).norm(), 1e-12 * angularMomentum.norm()) << h;
        // The explicit spin I⁻¹ L would turn L with the body (a first-order error): the test
        // tells them apart.
        const Vec3 explicitSpin = inertia.inverse() * angularMomentum;
        Quat explicitTurn = Quat::Identity();
        integrateRotation(explicitTurn, h * explicitSpin);
        const Vec3 explicitAfter = explicitTurn * Vec3(inertia * explicitSpin);
        EXPECT_GT((explicitAfter - angularMomentum).norm(), 1e-5 * angularMomentum.norm()) << h;
    }
}

TEST(RigidMode, NoSpinForParticlesOnALine) {
    // Inertia of masses on the x axis: zero about x, so no inverse and no turn, never a NaN.
    const Mat3 line = Vec3(0.0, 2.0, 2.0).asDiagonal();
    EXPECT_EQ(momentumKeepingSpin(line, Vec3(1, 1, 1), 1e-3), Vec3::Zero());
    EXPECT_EQ(momentumKeepingSpin(Mat3::Zero(), Vec3(1, 1, 1), 1e-3), Vec3::Zero());
}

}  // namespace
}  // namespace substep
