#pragma once
/// Per-element shape matching (Müller, Heidelberger, Teschner, Gross 2005) as an XPBD
/// constraint, and the element's optional volume constraint.
///
/// An element's corners x_j carry equal weights 1/8 (its mass is lumped equally to them) and
/// rest offsets q_j from the rest centroid (Σ q_j = 0). With c the current centroid and
/// A = Σ ⅛ (x_j − c) q_jᵀ, R is the rotation of A's polar decomposition, the goal is
/// g_j = c + R q_j and the constraint is the RMS distance to it:
///     C = sqrt(Σ ⅛ |x_j − g_j|²),  ∇_j C = ⅛ (x_j − g_j) / C.
/// (The gradient through c vanishes because Σ (x_j − g_j) = 0, and through R because R
/// minimises Σ |x_j − c − R q_j|².) XPBD: Δλ = (−C − α̃ λ) / (Σ w_j |∇_j C|² + α̃),
/// Δx_j = w_j ∇_j C Δλ, with α̃ = α_e / h². The corrections sum to zero momentum, and to zero
/// angular momentum because Σ (x_j − c) × R q_j = 0 for the polar rotation. α_e = α ℓ² / V
/// turns the material compliance α (1/Pa) into the element's: ℓ² = Σ ⅛ |q_j|², V the rest
/// volume, so the stored energy C² / (2 α_e) is V (C/ℓ)² / (2 α).
///
/// R is extracted iteratively (extractRotation: Newton steps, with the fallback of Müller,
/// Bender, Chentanez, Macklin 2016, "A Robust Method to Extract the Rotational Part of
/// Deformations"), warm-started from the element's rotation of the last substep rather than by
/// an SVD: it always returns a rotation, also for flat (rank 2), collapsed
/// (rank 0-1) and inverted (det A < 0) elements, where it keeps turning towards the closest
/// rotation it can find and otherwise stays put, so the goal is always the un-inverted rest
/// shape and the element recovers. A projection takes one Newton step of it (projectionRotation)
/// and leaves the rest to the next substep's.
///
/// Volume (optional): F = Σ x_j b_jᵀ with b_j = ⅛ A_qq⁻¹ q_j is the best-fit deformation
/// gradient (F = R at rest); C_V = det F − 1, ∇_j C_V = cof(F) b_j, compliance α_V / V.

#include "physics/math.h"
#include "physics/soft/lattice.h"

#include <array>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>

namespace substep {

/// Rotation-extraction iterations per call at most; warm-started, one or two suffice.
inline constexpr int kRotationIterations = 4;

/// A turn per Newton step beyond this (rad², 0.1 rad) is far off (a fresh, inverted or
/// collapsed element, or one turned hard in a substep): extractRotation turns it by its exact
/// angle and goes on, and projectionRotation hands it to extractRotation.
inline constexpr double kFarTurn2 = 0.01;

/// One step of extractRotation from the rotation matrix r: the turn δ (in r's frame) solving
/// (tr S 1 − S) δ = 2 u for B = rᵀ A = S + [u]×, and whether tr S 1 − S is positive definite
/// (where it is not, δ is Müller et al.'s 2016 (Eq. 7) 2 u / (|tr S| + ε)).
inline bool rotationStep(const Mat3& a, double epsilon, const Mat3& r, Vec3& turn) {
    const Mat3 b = r.transpose() * a;
    const Vec3 twiceU(b(2, 1) - b(1, 2), b(0, 2) - b(2, 0), b(1, 0) - b(0, 1));
    const double trace = b.trace();
    // M = tr S 1 − S (symmetric), solved by its adjugate; positive definite by its leading
    // minors m00, c22 and det.
    const double m00 = trace - b(0, 0), m11 = trace - b(1, 1), m22 = trace - b(2, 2);
    const double m01 = -0.5 * (b(0, 1) + b(1, 0)), m02 = -0.5 * (b(0, 2) + b(2, 0));
    const double m12 = -0.5 * (b(1, 2) + b(2, 1));
    const double c00 = m11 * m22 - m12 * m12, c01 = m02 * m12 - m01 * m22, c02 = m01 * m12 - m02 * m11;
    const double c11 = m00 * m22 - m02 * m02, c12 = m01 * m02 - m00 * m12, c22 = m00 * m11 - m01 * m01;
    const double det = m00 * c00 + m01 * c01 + m02 * c02;
    const double floor = 1e-6 * std::abs(trace) + epsilon;
    if (m00 > floor && c22 > floor * floor && det > floor * floor * floor) {
        turn = Vec3(c00 * twiceU.x() + c01 * twiceU.y() + c02 * twiceU.z(),
                    c01 * twiceU.x() + c11 * twiceU.y() + c12 * twiceU.z(),
                    c02 * twiceU.x() + c12 * twiceU.y() + c22 * twiceU.z()) /
               det;
        return true;
    }
    turn = twiceU / (std::abs(trace) + epsilon);
    return false;
}

/// Turns `rotation` towards the rotation R of A's polar decomposition A = R S. With
/// B = Rᵀ A = S + [u]× for the current R, the turn δ that makes B symmetric solves
/// (tr S 1 − S) δ = 2 u (Newton; quadratic convergence, one or two steps warm-started). Where
/// tr S 1 − S is not positive definite (an inverted or collapsed element) the step is Müller et
/// al.'s 2016 (Eq. 7) δ = 2 u / (|tr S| + ε), which always turns towards the closest rotation
/// and stays put when A vanishes. `scale` is A's natural size (ℓ²), which sets ε. Returns the new rotation as a matrix.
inline Mat3 extractRotation(const Mat3& a, double scale, Quat& rotation) {
    const double epsilon = 1e-9 * scale;
    Mat3 r = rotation.toRotationMatrix();
    for (int i = 0; i < kRotationIterations; ++i) {
        Vec3 turn;
        rotationStep(a, epsilon, r, turn);
        const double angle2 = turn.squaredNorm();
        if (!(angle2 > 1e-24)) break;  // converged (or NaN: keep the last rotation)
        const Vec3 omega = r * turn;   // into the world frame
        if (angle2 > kFarTurn2) {
            // Far off (a fresh or inverted element): turn by the exact angle, capped at π.
            const double angle = std::sqrt(angle2);
            rotation = (Quat(Eigen::AngleAxisd(std::min(angle, M_PI), omega / angle)) * rotation).normalized();
        } else {
            integrateRotation(rotation, omega);
        }
        r = rotation.toRotationMatrix();
        if (angle2 < 1e-6) break;  // Newton: what is left is about the square, 1e-6 rad
    }
    return r;
}

/// The rotation an element's projection uses (Eq. 4), warm-started from `rotation` (the last
/// substep's, turned with its body): one Newton step of extractRotation, where that step is
/// one (tr S 1 − S positive definite) of at most 0.1 rad; else extractRotation. A step from θ
/// off leaves about θ³/3 (measured, shape_matching_test; better than Newton's θ²), which the
/// next substep's step takes up: a tyre element rolling through the contact patch turns up to a
/// few mrad per substep after its body's turn, and stays within about 1e-8 rad of its polar
/// rotation. A second step, wherever any of the batch kernel's eight lanes needed one, cost
/// about a fifth of its time in rc_car.
inline Mat3 projectionRotation(const Mat3& a, double scale, Quat& rotation) {
    const Mat3 r = rotation.toRotationMatrix();
    Vec3 turn;
    const bool definite = rotationStep(a, 1e-9 * scale, r, turn);
    const double angle2 = turn.squaredNorm();
    if (!definite || !(angle2 <= kFarTurn2)) return extractRotation(a, scale, rotation);  // also NaN
    if (!(angle2 > 1e-24)) return r;  // converged
    integrateRotation(rotation, r * turn);
    return rotation.toRotationMatrix();
}

/// The element's best-fit linear map A = Σ ⅛ x_j q_jᵀ (Σ q_j = 0 removes the centroid).
inline Mat3 shapeMatrix(const std::array<Vec3, 8>& x, const std::array<Vec3, 8>& rest) {
    Mat3 a = Mat3::Zero();
    for (int j = 0; j < 8; ++j) a.noalias() += x[j] * rest[j].transpose();
    return a * 0.125;
}

/// C = sqrt(Σ ⅛ |x_j − c − R q_j|²) for the rotation matrix r; fills the deviations d_j.
inline double shapeMatchingError(const std::array<Vec3, 8>& x, const std::array<Vec3, 8>& rest,
                                 const Mat3& r, std::array<Vec3, 8>& deviation) {
    Vec3 centre = Vec3::Zero();
    for (int j = 0; j < 8; ++j) centre += x[j];
    centre *= 0.125;
    double sum = 0.0;
    for (int j = 0; j < 8; ++j) {
        deviation[j] = x[j] - centre - r * rest[j];
        sum += deviation[j].squaredNorm();
    }
    return std::sqrt(0.125 * sum);
}

/// det F − 1 for F = Σ x_j b_jᵀ; fills ∇_j (det F − 1) = cof(F) b_j.
inline double volumeError(const std::array<Vec3, 8>& x, const std::array<Vec3, 8>& b,
                          std::array<Vec3, 8>& gradient) {
    Mat3 f = Mat3::Zero();
    for (int j = 0; j < 8; ++j) f.noalias() += x[j] * b[j].transpose();
    Mat3 cofactor;
    cofactor.col(0) = f.col(1).cross(f.col(2));
    cofactor.col(1) = f.col(2).cross(f.col(0));
    cofactor.col(2) = f.col(0).cross(f.col(1));
    for (int j = 0; j < 8; ++j) gradient[j] = cofactor * b[j];
    return f.col(0).dot(cofactor.col(0)) - 1.0;
}

}  // namespace substep
