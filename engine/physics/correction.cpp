#include "physics/correction.h"

#include "physics/correction_kernels.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

namespace substep {

using namespace correction_kernels;  // the operations' inner steps (correction_kernels.h)

namespace {

/// One body's side of a correction along a unit direction: its generalised inverse mass and
/// the rotation per unit multiplier, computed once and used for both: w is Eq. 2 or Eq. 3
/// (positional) or Eq. 11 or Eq. 12 (angular); the rotation is the one Eq. 8 and Eq. 9 (or
/// Eq. 15 and Eq. 16) apply per unit Δλ.
struct BodyResponse {
    double w = 0.0;                ///< generalised inverse mass
    Vec3 rotationPerUnit = Vec3::Zero();  ///< world rotation per unit Δλ: I⁻¹ (r × n) or I⁻¹ n
};

/// Response to a positional correction along n at world offset r.
inline BodyResponse positionalResponse(const Body& body, const Vec3& r, const Vec3& n) {
    if (body.invMass == 0.0) return {};
    if (!body.rotates()) return {body.invMass, Vec3::Zero()};
    if (body.isotropic) {
        const Vec3 rn = r.cross(n);
        return {body.invMass + body.invInertia.x() * rn.squaredNorm(), body.invInertia.x() * rn};
    }
    const Vec3 rn = body.q.conjugate() * r.cross(n);  // into the rest frame (paper 3.3.2)
    const Vec3 invInertiaRn = body.invInertia.cwiseProduct(rn);
    return {body.invMass + rn.dot(invInertiaRn), body.q * invInertiaRn};
}

/// World inverse inertia R diag(I⁻¹) Rᵀ at `orientation` (zero for bodies that do not rotate).
inline Mat3 worldInverseInertia(const Body& body, const Quat& orientation) {
    if (!body.rotates() || body.invMass == 0.0) return Mat3::Zero();
    const Mat3 r = orientation.toRotationMatrix();
    return r * body.invInertia.asDiagonal() * r.transpose();
}

}  // namespace

Vec3 applyPositionalCorrection(SolverContext& ctx, uint32_t i0, uint32_t i1, const Vec3& delta,
                               const Vec3& r0, const Vec3& r1, double compliance, double& lambda,
                               double lambdaLimit) {
    const double c = delta.norm();
    // A zero correction has no direction; there is nothing to do (and no NaN to make).
    if (!(c > kDirectionEpsilon)) return Vec3::Zero();
    if (skippedByRepair(ctx, c, ctx.repairDistance, compliance)) return Vec3::Zero();
    const Vec3 n = delta / c;
    const Body& b0 = ctx.bodies[i0];
    const Body& b1 = ctx.bodies[i1];
    const BodyResponse s0 = positionalResponse(b0, r0, n);  // Eq. 2
    const BodyResponse s1 = positionalResponse(b1, r1, n);  // Eq. 3
    const double alphaTilde = compliance * ctx.invH2;
    const double denominator = s0.w + s1.w + alphaTilde;
    if (!(denominator > 0.0)) return Vec3::Zero();  // two static bodies
    // Eq. 4 with ERRATA item 1's sign: λ grows with the stretch c, so f = λ n / h² (Eq. 10).
    const double deltaLambda = (c - alphaTilde * lambda) / denominator;
    if (lambda + deltaLambda > lambdaLimit) return Vec3::Zero();
    lambda += deltaLambda;  // Eq. 5
    const Vec3 p = deltaLambda * n;
    moveBody(ctx, i0, p * b0.invMass, s0.rotationPerUnit * deltaLambda);    // Eq. 6, Eq. 8
    moveBody(ctx, i1, -p * b1.invMass, -s1.rotationPerUnit * deltaLambda);  // Eq. 7, Eq. 9
    return p;
}

void applyWeldCorrection(SolverContext& ctx, uint32_t i0, uint32_t i1, const Vec3& delta,
                         const Vec3& r0, const Vec3& r1, const Vec3& rotation, double compliance,
                         Vec3& lambdaPoint, Vec3& lambdaAngle, Vec3& impulse, Vec3& angularImpulse) {
    if (ctx.repairDistance > 0.0 &&
        skippedByRepair(ctx, std::max(delta.norm() / ctx.repairDistance, rotation.norm() / ctx.repairAngle),
                        1.0, compliance))
        return;
    const Body& b0 = ctx.bodies[i0];
    const Body& b1 = ctx.bodies[i1];
    const Mat3 invInertia0 = worldInverseInertia(b0, directionOrientation(ctx, b0));
    const Mat3 invInertia1 = worldInverseInertia(b1, directionOrientation(ctx, b1));
    const Mat3 cross0 = crossMatrix(r0);
    const Mat3 cross1 = crossMatrix(r1);
    // K for an impulse P at the anchors and an angular impulse L: the gap closes by
    // (w0 + w1) P − Σ [r]× I⁻¹ ([r]× P + L), the rotation by Σ I⁻¹ ([r]× P + L).
    const double alphaTilde = compliance * ctx.invH2;
    Eigen::Matrix<double, 6, 6> k;
    k.topLeftCorner<3, 3>() = -(cross0 * invInertia0 * cross0 + cross1 * invInertia1 * cross1);
    k.topLeftCorner<3, 3>().diagonal().array() += b0.invMass + b1.invMass + alphaTilde;
    k.topRightCorner<3, 3>() = -(cross0 * invInertia0 + cross1 * invInertia1);
    k.bottomLeftCorner<3, 3>() = invInertia0 * cross0 + invInertia1 * cross1;
    k.bottomRightCorner<3, 3>() = invInertia0 + invInertia1;
    Eigen::Matrix<double, 6, 1> rhs;
    rhs << delta - alphaTilde * lambdaPoint, rotation;
    const Eigen::FullPivLU<Eigen::Matrix<double, 6, 6>> lu(k);
    if (lu.rank() < 6) return;  // two static bodies
    const Eigen::Matrix<double, 6, 1> step = lu.solve(rhs);
    if (!step.allFinite()) return;
    const Vec3 p = step.head<3>();
    const Vec3 l = step.tail<3>();
    lambdaPoint += p;
    lambdaAngle += l;
    impulse += p;
    angularImpulse += l;
    moveBody(ctx, i0, p * b0.invMass, invInertia0 * (r0.cross(p) + l));
    moveBody(ctx, i1, -p * b1.invMass, -(invInertia1 * (r1.cross(p) + l)));
}

Vec3 applyAngularCorrection(SolverContext& ctx, uint32_t i0, uint32_t i1, const Vec3& rotation,
                            double compliance, double& lambda, double lambdaLimit) {
    return applyAngularCorrection(ctx, i0, i1, ctx.bodies[i0].q.toRotationMatrix(),
                                  ctx.bodies[i1].q.toRotationMatrix(), rotation, compliance, lambda,
                                  lambdaLimit);
}

Vec3 applyAngularCorrection(SolverContext& ctx, uint32_t i0, uint32_t i1, const Mat3& rotation0,
                            const Mat3& rotation1, const Vec3& rotation, double compliance,
                            double& lambda, double lambdaLimit) {
    return angularCorrection(ctx, i0, i1, rotation0, rotation1, rotation, compliance, lambda, lambdaLimit);
}

Vec3 applyPointCorrection(SolverContext& ctx, uint32_t i0, uint32_t i1, const Vec3& delta,
                          const Vec3& r0, const Vec3& r1, double compliance, Vec3& lambda) {
    return applyPointCorrection(ctx, i0, i1, ctx.bodies[i0].q.toRotationMatrix(),
                                ctx.bodies[i1].q.toRotationMatrix(), delta, r0, r1, compliance, lambda);
}


Vec3 applyPointCorrection(SolverContext& ctx, uint32_t i0, uint32_t i1, const Mat3& rotation0,
                          const Mat3& rotation1, const Vec3& delta, const Vec3& r0, const Vec3& r1,
                          double compliance, Vec3& lambda) {
    return pointCorrection(ctx, i0, i1, rotation0, rotation1, delta, r0, r1, compliance, lambda);
}

Vec3 applyAttachmentCorrection(SolverContext& ctx, uint32_t i0, uint32_t i1,
                               const Vec3& anchor0, const Vec3& anchor1, double compliance,
                               Vec3& lambda) {
    return attachmentCorrection(ctx, i0, i1, anchor0, anchor1, compliance, lambda);
}

Vec3 applyRotationCorrection(SolverContext& ctx, uint32_t i0, uint32_t i1, const Vec3& rotation,
                             double compliance, Vec3& lambda, const Vec3* freeAxis) {
    const Body& b0 = ctx.bodies[i0];
    const Body& b1 = ctx.bodies[i1];
    return applyRotationCorrection(ctx, i0, i1, directionOrientation(ctx, b0).toRotationMatrix(),
                                   directionOrientation(ctx, b1).toRotationMatrix(), rotation,
                                   compliance, lambda, freeAxis);
}

Vec3 applyRotationCorrection(SolverContext& ctx, uint32_t i0, uint32_t i1, const Mat3& rotation0,
                             const Mat3& rotation1, const Vec3& rotation, double compliance,
                             Vec3& lambda, const Vec3* freeAxis) {
    return rotationCorrection(ctx, i0, i1, rotation0, rotation1, rotation, compliance, lambda, freeAxis);
}

void applyImpulse(SolverContext& ctx, uint32_t i0, uint32_t i1, const Vec3& linear,
                  const Vec3& angular0, const Vec3& angular1) {
    const Body& b0 = ctx.bodies[i0];
    const Body& b1 = ctx.bodies[i1];
    if (b0.invMass > 0.0)
        moveBody(ctx, i0, linear * b0.invMass,
                 b0.rotates() ? b0.applyInverseInertia(angular0) : Vec3::Zero());
    if (b1.invMass > 0.0)
        moveBody(ctx, i1, -linear * b1.invMass,
                 b1.rotates() ? Vec3(-b1.applyInverseInertia(angular1)) : Vec3::Zero());
}

Vec3 applyVelocityCorrection(Body& b0, Body& b1, const Vec3& deltaVelocity, const Vec3& r0,
                             const Vec3& r1) {
    const double magnitude = deltaVelocity.norm();
    if (!(magnitude > kDirectionEpsilon)) return Vec3::Zero();
    const Vec3 n = deltaVelocity / magnitude;
    const double w = b0.positionalInverseMass(r0, n) + b1.positionalInverseMass(r1, n);
    if (!(w > 0.0)) return Vec3::Zero();
    const Vec3 p = deltaVelocity / w;  // Eq. 33: p = Δv / (w1 + w2), then v and ω of both bodies
    if (b0.invMass > 0.0) {
        b0.v += p * b0.invMass;
        if (b0.rotates()) b0.omega += b0.applyInverseInertia(r0.cross(p));
    }
    if (b1.invMass > 0.0) {
        b1.v -= p * b1.invMass;
        if (b1.rotates()) b1.omega -= b1.applyInverseInertia(r1.cross(p));
    }
    return p;
}

Vec3 applyAngularVelocityCorrection(Body& b0, Body& b1, const Vec3& deltaOmega) {
    return angularVelocityCorrection(b0, b1, deltaOmega);
}

void applyJacobiDeltas(Body* bodies, JacobiDelta* deltas, size_t count) {
    for (size_t i = 0; i < count; ++i) {
        JacobiDelta& d = deltas[i];
        if (d.count == 0) continue;
        bodies[i].x += d.position;
        if (bodies[i].rotates()) addRotation(bodies[i].q, d.rotation);
        d.position.setZero();
        d.rotation.setZero();
        d.count = 0;
    }
}

}  // namespace substep
