// Tests engine/physics/soft/shape_matching.h: the warm-started rotation extraction against the
// polar decomposition, a projection's one Newton step and its convergence, and the guards for
// inverted, flat and collapsed elements.
#include "physics/soft/shape_matching.h"

#include <gtest/gtest.h>

#include <Eigen/SVD>

namespace substep {
namespace {

Quat someRotation(double angle, const Vec3& axis) { return Quat(Eigen::AngleAxisd(angle, axis.normalized())); }

/// Rotation of the polar decomposition A = R S by SVD (det > 0).
Mat3 polarRotation(const Mat3& a) {
    Eigen::JacobiSVD<Mat3> svd(a, Eigen::ComputeFullU | Eigen::ComputeFullV);
    return svd.matrixU() * svd.matrixV().transpose();
}

TEST(ShapeMatching, RotationExtractionFindsThePolarRotation) {
    Mat3 s;  // symmetric positive definite stretch
    s << 1.3, 0.2, -0.1, 0.2, 0.8, 0.05, -0.1, 0.05, 1.1;
    for (double angle : {0.1, 1.0, 2.5}) {
        const Mat3 r = someRotation(angle, Vec3(1, 2, 3)).toRotationMatrix();
        const Mat3 a = r * s;
        // Cold start far away, then warm: the iteration converges within its budget a few calls.
        Quat q = Quat::Identity();
        for (int call = 0; call < 5; ++call) extractRotation(a, 1.0, q);
        EXPECT_LT((q.toRotationMatrix() - polarRotation(a)).norm(), 1e-7) << angle;
    }
}

TEST(ShapeMatching, WarmStartConvergesInOneCall) {
    Mat3 s = Mat3::Identity();
    s(0, 0) = 1.2;
    const Quat truth = someRotation(0.7, Vec3(0, 1, 1));
    Quat q = someRotation(0.69, Vec3(0, 1, 1));  // last substep's rotation
    extractRotation(truth.toRotationMatrix() * s, 1.0, q);
    EXPECT_LT(q.angularDistance(truth), 1e-8);
}

TEST(ShapeMatching, ProjectionTakesOneNewtonStepAndLeavesAboutItsCube) {
    // A stretch and axes not tuned for: a warm start θ off the polar rotation. One Newton step
    // (θ ≤ 0.1 rad) leaves an error of order θ³ here (about θ³/3: the step solves the symmetry
    // of Rᵀ A to first order, and its second-order term vanishes by that symmetry), at most the
    // θ² of Newton's quadratic convergence, and it is one step only: a second call from there
    // moves by that error. Beyond 0.1 rad, or not positive definite, it is extractRotation's
    // whole result.
    Mat3 s;
    s << 1.3, 0.2, -0.1, 0.2, 0.8, 0.05, -0.1, 0.05, 1.1;
    for (const Vec3& axis : {Vec3(1, 2, 3), Vec3(-2, 0.5, 1), Vec3(0, 0, 1)}) {
        const Quat truth = someRotation(1.1, Vec3(3, -1, 2));
        const Mat3 a = truth.toRotationMatrix() * s;
        const Quat polar(polarRotation(a));
        for (const double theta : {1e-4, 1e-3, 0.01, 0.05, 0.099}) {
            const Quat start = someRotation(theta, axis) * polar;
            Quat q = start;
            const Mat3 r = projectionRotation(a, 1.0, q);
            EXPECT_LT((r - q.toRotationMatrix()).norm(), 1e-15);
            const double left = q.angularDistance(polar);
            EXPECT_LT(left, theta * theta * theta) << theta;
            EXPECT_GT(left, 0.1 * theta * theta * theta) << theta;  // one step, not converged to rounding
            if (left > 1e-11) {  // (a smaller turn counts as converged: (1e-12)² ≤ 1e-24)
                Quat again = q;
                projectionRotation(a, 1.0, again);
                EXPECT_NEAR(again.angularDistance(q), left, 0.01 * left) << theta;
            }
            // Substep after substep from the same matrix, the warm start converges.
            for (int call = 0; call < 3; ++call) projectionRotation(a, 1.0, q);
            EXPECT_LT(q.angularDistance(polar), 1e-12) << theta;
        }
        // Far off: the same as extractRotation.
        for (const double theta : {0.3, 2.0}) {
            Quat q = someRotation(theta, axis) * polar, full = q;
            const Mat3 r = projectionRotation(a, 1.0, q), expected = extractRotation(a, 1.0, full);
            EXPECT_EQ(q.coeffs(), full.coeffs()) << theta;
            EXPECT_EQ(r, expected) << theta;
        }
    }
    // Fully inverted (tr S 1 − S not positive definite): extractRotation's fallback, also the same.
    const Mat3 inverted = -Mat3::Identity();
    Quat q = someRotation(0.02, Vec3(1, 0, 0)), full = q;
    projectionRotation(inverted, 1.0, q), extractRotation(inverted, 1.0, full);
    EXPECT_EQ(q.coeffs(), full.coeffs());
}

TEST(ShapeMatching, InvertedFlatAndCollapsedElementsGiveARotation) {
    const Quat previous = someRotation(0.3, Vec3(1, 0, 0));
    const Mat3 r = previous.toRotationMatrix();
    const Mat3 cases[] = {
        r * Vec3(1.0, 1.0, -0.5).asDiagonal().toDenseMatrix(),  // inverted through z
        r * Vec3(1.0, 1.0, 0.0).asDiagonal().toDenseMatrix(),   // flat
        r * Vec3(1.0, 0.0, 0.0).asDiagonal().toDenseMatrix(),   // collapsed to a line
        Mat3::Zero(),                                           // collapsed to a point
        -r,                                                     // fully inverted
    };
    for (const Mat3& a : cases) {
        Quat q = previous;
        extractRotation(a, 1.0, q);
        EXPECT_TRUE(q.coeffs().allFinite());
        EXPECT_NEAR(q.norm(), 1.0, 1e-12);
        EXPECT_NEAR(q.toRotationMatrix().determinant(), 1.0, 1e-12);
    }
    // Inverted, flat and collapsed along z, the rotation about x that fits the rest stays put.
    for (int k = 0; k < 3; ++k) {
        Quat q = previous;
        extractRotation(cases[k], 1.0, q);
        EXPECT_LT(q.angularDistance(previous), 1e-6) << k;
    }
    Quat q = previous;
    extractRotation(Mat3::Zero(), 1.0, q);
    EXPECT_EQ(q.coeffs(), previous.coeffs());
}

TEST(ShapeMatching, ErrorVanishesForARigidMotionAndMeasuresAStretch) {
    std::array<Vec3, 8> rest;
    for (int n = 0; n < 8; ++n) rest[n] = Vec3((n & 1) - 0.5, ((n >> 1) & 1) - 0.5, ((n >> 2) & 1) - 0.5);
    const Quat turn = someRotation(0.9, Vec3(1, -1, 2));
    std::array<Vec3, 8> x;
    for (int n = 0; n < 8; ++n) x[n] = Vec3(3, 4, 5) + turn * rest[n];
    Quat q = Quat::Identity();
    for (int call = 0; call < 4; ++call) extractRotation(shapeMatrix(x, rest), 0.75, q);
    std::array<Vec3, 8> d;
    EXPECT_LT(shapeMatchingError(x, rest, q.toRotationMatrix(), d), 1e-9);
    // Compressed by δ along y: every corner is δ/2 from its goal, so C = δ/2.
    for (int n = 0; n < 8; ++n) x[n] = rest[n] + Vec3(0, -0.1 * rest[n].y(), 0);
    q = Quat::Identity();
    extractRotation(shapeMatrix(x, rest), 0.75, q);
    EXPECT_NEAR(shapeMatchingError(x, rest, q.toRotationMatrix(), d), 0.05, 1e-12);
    // det F − 1 for the same compression is −0.1.
    Mat3 aqq = Mat3::Zero();
    for (const Vec3& p : rest) aqq += 0.125 * p * p.transpose();
    std::array<Vec3, 8> b;
    for (int n = 0; n < 8; ++n) b[n] = 0.125 * (aqq.inverse() * rest[n]);
    EXPECT_NEAR(volumeError(x, b, d), -0.1, 1e-12);
}

}  // namespace
}  // namespace substep
