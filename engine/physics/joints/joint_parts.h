#pragma once
/// The parts joints are assembled from, as Jolt assembles constraints from its constraint parts:
/// each part owns its Lagrange multiplier λ (paper 3.3.1, zeroed every substep) and the impulse
/// it gave body 0 in the current substep, and moves the bodies through one of the correction
/// operations of correction.h. A joint type is a few named parts; resetting multipliers and
/// reading forces and torques loop over them (Joint::resetMultipliers, Joint::linearImpulse).
///
/// Each part reads the bodies' current state when it is solved, so every part sees the
/// corrections made before it (non-linear Gauss-Seidel, paper section 1).
///
///   PointPart     an attachment, 3.4.2 (vector λ, block form of the positional correction)
///   AxisPart      a positional correction along one direction, 3.3.1 (scalar λ)
///   RotationPart  an orientation lock or axis alignment (vector λ, block angular correction)
///   AnglePart     an angular correction about one axis, 3.3.2, or Algorithm 3's angle limit
/// The first two give forces (Eq. 10), the last two torques (Eq. 17).

#include "physics/correction.h"

#include <cmath>

namespace substep {

/// Attachment (3.4.2): makes body 0's anchor coincide with body 1's, Δx = Δr = p1 − p0, with
/// the full 3 x 3 inverse mass (applyPointCorrection explains why).
struct PointPart {
    static constexpr bool kAngular = false;
    Vec3 lambda = Vec3::Zero();   ///< vector multiplier
    Vec3 impulse = Vec3::Zero();  ///< given to body 0 this substep

    void reset() {
        lambda.setZero();
        impulse.setZero();
    }
    /// Anchors in the bodies' principal frames (Joint::anchor0, anchor1).
    void solve(SolverContext& ctx, uint32_t body0, uint32_t body1, const Vec3& anchor0,
               const Vec3& anchor1, double compliance) {
        impulse += applyAttachmentCorrection(ctx, body0, body1, anchor0, anchor1, compliance, lambda);
    }
    /// With the gap delta = p1 − p0, the lever arms and the matrices they were taken on computed
    /// by the joint (joint_geometry.h's JointRotations), which shares them between its parts.
    void solve(SolverContext& ctx, uint32_t body0, uint32_t body1, const Mat3& rotation0,
               const Mat3& rotation1, const Vec3& delta, const Vec3& arm0, const Vec3& arm1,
               double compliance) {
        impulse += applyPointCorrection(ctx, body0, body1, rotation0, rotation1, delta, arm0, arm1,
                                        compliance, lambda);
    }
};

/// Positional correction (3.3.1, Eq. 2 to Eq. 9 in applyPositionalCorrection): moves the
/// point at offset r0 of body 0 by `delta` relative to the point at r1 of body 1.
struct AxisPart {
    static constexpr bool kAngular = false;
    double lambda = 0.0;
    Vec3 impulse = Vec3::Zero();  ///< given to body 0 this substep

    void reset() {
        lambda = 0.0;
        impulse.setZero();
    }
    void solve(SolverContext& ctx, uint32_t body0, uint32_t body1, const Vec3& delta,
               const Vec3& r0, const Vec3& r1, double compliance) {
        impulse += applyPositionalCorrection(ctx, body0, body1, delta, r0, r1, compliance, lambda);
    }
};

/// Orientation lock or axis alignment in block form (applyRotationCorrection says why): turns
/// body 0 by the world rotation vector `rotation` relative to body 1; with `freeAxis`, only
/// about the two directions normal to it.
struct RotationPart {
    static constexpr bool kAngular = true;
    Vec3 lambda = Vec3::Zero();   ///< vector multiplier
    Vec3 impulse = Vec3::Zero();  ///< angular, given to body 0 this substep

    void reset() {
        lambda.setZero();
        impulse.setZero();
    }
    void solve(SolverContext& ctx, uint32_t body0, uint32_t body1, const Vec3& rotation,
               double compliance, const Vec3* freeAxis = nullptr) {
        impulse += applyRotationCorrection(ctx, body0, body1, rotation, compliance, lambda, freeAxis);
    }
    /// With the matrices of the orientations directionOrientation names.
    void solve(SolverContext& ctx, uint32_t body0, uint32_t body1, const Mat3& rotation0,
               const Mat3& rotation1, const Vec3& rotation, double compliance,
               const Vec3* freeAxis = nullptr) {
        impulse += applyRotationCorrection(ctx, body0, body1, rotation0, rotation1, rotation,
                                           compliance, lambda, freeAxis);
    }
};

/// How far the angle φ lies beyond [lower, upper] (Algorithm 3 with ERRATA items 3-4): φ minus
/// the bound it passed, taken the short way round; 0 inside.
inline double limitExcess(double phi, double lower, double upper) {
    if (phi >= lower && phi <= upper) return 0.0;
    double excess = phi - (phi < lower ? lower : upper);
    if (excess > M_PI) excess -= 2.0 * M_PI;
    if (excess <= -M_PI) excess += 2.0 * M_PI;
    return excess;
}

/// Angular correction (3.3.2, Eq. 11 to Eq. 16 in applyAngularCorrection): turns body 0 by
/// `rotation` relative to body 1; or, as a limit, Algorithm 3.
struct AnglePart {
    static constexpr bool kAngular = true;
    double lambda = 0.0;
    Vec3 impulse = Vec3::Zero();  ///< angular, given to body 0 this substep

    void reset() {
        lambda = 0.0;
        impulse.setZero();
    }
    void solve(SolverContext& ctx, uint32_t body0, uint32_t body1, const Vec3& rotation,
               double compliance) {
        impulse += applyAngularCorrection(ctx, body0, body1, rotation, compliance, lambda);
    }
    /// With the matrices of the bodies' current orientations.
    void solve(SolverContext& ctx, uint32_t body0, uint32_t body1, const Mat3& rotation0,
               const Mat3& rotation1, const Vec3& rotation, double compliance) {
        impulse += applyAngularCorrection(ctx, body0, body1, rotation0, rotation1, rotation,
                                          compliance, lambda);
    }
    /// Algorithm 3 (with ERRATA items 3-4): keeps the angle from n0 to n1 about n inside
    /// [lower, upper]. n, n0, n1 are unit vectors, n0 and n1 perpendicular to n.
    void solveLimit(SolverContext& ctx, uint32_t body0, uint32_t body1, const Vec3& n,
                    const Vec3& n0, const Vec3& n1, double lower, double upper, double compliance) {
        // Algorithm 3: φ = asin((n1 × n2)·n), taken as the full signed angle (ERRATA item 3).
        const double phi = signedAngle(n, n0, n1);
        if (phi >= lower && phi <= upper) return;
        const double clamped = phi < lower ? lower : upper;
        // n0 and n1 lie in the plane normal to n, so the turn from the limit's direction to n1
        // is about n by the excess, taken the short way round: no need to build that direction.
        double excess = phi - clamped;
        if (excess > M_PI) excess -= 2.0 * M_PI;
        if (excess <= -M_PI) excess += 2.0 * M_PI;
        solve(ctx, body0, body1, excess * n, compliance);
    }
    /// The same with the matrices of the bodies' current orientations, and φ measured by the
    /// caller (limitExcess): a joint that has the angle at hand for its other parts passes it on.
    void solveLimit(SolverContext& ctx, uint32_t body0, uint32_t body1, const Mat3& rotation0,
                    const Mat3& rotation1, const Vec3& n, double phi, double lower, double upper,
                    double compliance) {
        const double excess = limitExcess(phi, lower, upper);
        if (excess != 0.0) solve(ctx, body0, body1, rotation0, rotation1, excess * n, compliance);
    }
};

/// How far the angle from n0 to n1 about n lies outside [lower, upper] (rad).
inline double angleLimitViolation(const Vec3& n, const Vec3& n0, const Vec3& n1, double lower,
                                  double upper) {
    const double phi = signedAngle(n, n0, n1);
    return phi < lower ? lower - phi : (phi > upper ? phi - upper : 0.0);
}

/// Energy C²/(2α) of a compliant part with violation c; hard parts store none.
inline double elasticEnergy(double violation, double compliance) {
    return compliance > 0.0 ? violation * violation / (2.0 * compliance) : 0.0;
}

}  // namespace substep
