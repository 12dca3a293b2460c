// Tests engine/physics/gyroscopic_step.h: the implicit gyroscopic step against the Newton system
// it solves (J δ = h ω × Iω, J = I + h ([ω]× I − [Iω]×), solved here by Eigen's LU), for one,
// two and three distinct moments, each distinct moment on each principal axis, and its skip.

#include "physics/gyroscopic_step.h"

#include <Eigen/LU>
#include <gtest/gtest.h>

#include <cmath>

namespace substep {
namespace {

/// The Newton step in the principal frame, solved by LU: the defining equation, independently.
Vec3 newtonStep(const Vec3& omega, const Vec3& inertia, double h) {
    const Mat3 inertiaMatrix = inertia.asDiagonal();
    const Vec3 momentum = inertiaMatrix * omega;
    const Mat3 jacobian = inertiaMatrix + h * (crossMatrix(omega) * inertiaMatrix - crossMatrix(momentum));
    return omega - jacobian.fullPivLu().solve(h * omega.cross(momentum));
}

Body boxBody(const Vec3& size, const Quat& orientation, const Vec3& omega) {
    return makeBody({.shape = boxShape(size), .mass = 2.0, .orientation = orientation, .angularVelocity = omega});
}

TEST(GyroscopicStepTest, DistinctMomentNamesTheAxisThatDiffers) {
    EXPECT_EQ(distinctMoment(Vec3(1, 1, 1)), -1);
    EXPECT_EQ(distinctMoment(Vec3(1, 2, 3)), -1);
    EXPECT_EQ(distinctMoment(Vec3(1, 1, 3)), 2);
    EXPECT_EQ(distinctMoment(Vec3(3, 1, 1)), 0);
    EXPECT_EQ(distinctMoment(Vec3(1, 3, 1)), 1);
}

// Three equal moments: ω × Iω = 0, and the step returns ω bit for bit (a cube, a sphere).
TEST(GyroscopicStepTest, EqualMomentsLeaveOmegaExactly) {
    const Quat q(Eigen::AngleAxisd(0.9, Vec3(1, -2, 0.5).normalized()));
    const Vec3 omega(3.0, -7.0, 11.0);
    for (const Body& body : {boxBody(Vec3(0.2, 0.2, 0.2), q, omega),
                             makeBody({.shape = sphereShape(0.3), .mass = 1.0, .orientation = q,
                                       .angularVelocity = omega})}) {
        ASSERT_TRUE(body.isotropic);
        const Vec3 after = gyroscopicStep(body, 1.0 / 600.0);
        EXPECT_EQ(after.x(), body.omega.x());
        EXPECT_EQ(after.y(), body.omega.y());
        EXPECT_EQ(after.z(), body.omega.z());
    }
}

// Two equal moments (the closed form about the symmetry axis) and three different ones (the
// cofactor solve) give the Newton step of the defining equation, for each orientation, each axis
// the distinct moment lies on, thin and flat bodies, and h ω from small to large.
TEST(GyroscopicStepTest, StepSolvesTheNewtonSystem) {
    const Vec3 sizes[] = {{0.1, 0.1, 0.6}, {0.6, 0.1, 0.1}, {0.1, 0.6, 0.1},  // rods along z, x, y
                          {0.5, 0.5, 0.05}, {0.05, 0.5, 0.5},                   // plates
                          {0.1, 0.2, 0.3},  {0.7, 0.02, 0.3}};                  // three moments
    const Quat orientations[] = {Quat::Identity(), Quat(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized())),
                                 Quat(Eigen::AngleAxisd(2.9, Vec3(-3, 1, 0.2).normalized()))};
    const Vec3 omegas[] = {{0.3, -0.2, 5.0}, {40.0, -12.0, 3.0}, {-200.0, 150.0, 90.0}};
    for (const Vec3& size : sizes)
        for (const Quat& q : orientations)
            for (const Vec3& omega : omegas)
                for (const double h : {1.0 / 1200.0, 1.0 / 60.0}) {
                    const Body body = boxBody(size, q, omega);
                    ASSERT_FALSE(body.isotropic);
                    const Vec3 expected = body.q * newtonStep(body.q.conjugate() * body.omega, body.inertia, h);
                    const Vec3 step = gyroscopicStep(body, h);
                    EXPECT_LT((step - expected).norm(), 1e-12 * omega.norm())
                        << "size " << size.transpose() << " omega " << omega.transpose() << " h " << h;
                }
}

// The step never turns the spin about a symmetry axis: ω · axis is kept to rounding, and with ω
// along the axis nothing changes at all (a spinning wheel keeps its rate).
TEST(GyroscopicStepTest, AxisymmetricStepKeepsTheAxialSpin) {
    const Quat q(Eigen::AngleAxisd(1.1, Vec3(0.3, 1, -2).normalized()));
    const Body rod = boxBody(Vec3(0.1, 0.1, 0.6), q, q * Vec3(4.0, -3.0, 25.0));
    const Vec3 axis = rod.userOrientation() * Vec3::UnitZ();
    const Vec3 after = gyroscopicStep(rod, 1.0 / 300.0);
    EXPECT_NEAR(after.dot(axis), 25.0, 1e-12 * 25.0);
    // The transverse part shrinks by 1/√(1 + t²) (implicit Euler), never grows.
    EXPECT_LT((after - after.dot(axis) * axis).norm(), 5.0);
    const Body wheel = boxBody(Vec3(0.1, 0.1, 0.6), q, q * Vec3(0.0, 0.0, 25.0));
    EXPECT_LT((gyroscopicStep(wheel, 1.0 / 300.0) - wheel.omega).norm(), 1e-13);
}

}  // namespace
}  // namespace substep
