#include "physics/correction.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

namespace substep {
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

/// Response to a rotation about unit n.
inline BodyResponse angularResponse(const Body& body, const Vec3& n) {
    if (body.invMass == 0.0 || !body.rotates()) return {};
    const Vec3 nb = body.q.conjugate() * n;
    const Vec3 invInertiaN = body.invInertia.cwiseProduct(nb);
    return {nb.dot(invInertiaN), body.q * invInertiaN};
}

/// In the repair pass, whether a correction of this size and compliance is left alone: the pass
/// only moves hard parts that are far from satisfied. Counts the ones it makes.
inline bool skippedByRepair(SolverContext& ctx, double size, double threshold, double compliance) {
    if (threshold == 0.0) return false;  // not repairing
    if (compliance > 0.0 || size < threshold) return true;
    ++ctx.repairs;
    return false;
}

/// Moves body `index` by dx and turns it by dtheta (the position update of Eq. 6 or Eq. 7, the
/// rotation of Eq. 8, Eq. 9, Eq. 15 or Eq. 16, applied by the exact exponential map rather than
/// the linearised quaternion update), or gathers them for Jacobi.
inline void moveBody(SolverContext& ctx, uint32_t index, const Vec3& dx, const Vec3& dtheta) {
    Body& body = ctx.bodies[index];
    if (body.invMass == 0.0) return;
    if (ctx.solver == SolverType::Jacobi) {
        JacobiDelta& d = ctx.deltas[index];
        d.position += dx;
        d.rotation += dtheta;
        ++d.count;
        return;
    }
    body.x += dx;
    if (body.rotates()) integrateRotation(body.q, dtheta);
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
    const double theta = rotation.norm();
    if (!(theta > kDirectionEpsilon)) return Vec3::Zero();
    if (skippedByRepair(ctx, theta, ctx.repairAngle, compliance)) return Vec3::Zero();
    const Vec3 n = rotation / theta;
    const BodyResponse s0 = angularResponse(ctx.bodies[i0], n);  // Eq. 11
    const BodyResponse s1 = angularResponse(ctx.bodies[i1], n);  // Eq. 12
    const double alphaTilde = compliance * ctx.invH2;
    const double denominator = s0.w + s1.w + alphaTilde;
    if (!(denominator > 0.0)) return Vec3::Zero();
    // Eq. 13 with ERRATA item 1's sign (θ rather than −θ).
    const double deltaLambda = (theta - alphaTilde * lambda) / denominator;
    if (lambda + deltaLambda > lambdaLimit) return Vec3::Zero();
    lambda += deltaLambda;                                                  // Eq. 14
    moveBody(ctx, i0, Vec3::Zero(), s0.rotationPerUnit * deltaLambda);   // Eq. 15
    moveBody(ctx, i1, Vec3::Zero(), -s1.rotationPerUnit * deltaLambda);  // Eq. 16
    return deltaLambda * n;
}

namespace {

/// A symmetric 3 x 3 matrix by its six entries (the point correction's K).
struct Symmetric3 {
    double xx = 0, yy = 0, zz = 0, xy = 0, xz = 0, yz = 0;
    Vec3 times(const Vec3& v) const {
        return {xx * v.x() + xy * v.y() + xz * v.z(), xy * v.x() + yy * v.y() + yz * v.z(),
                xz * v.x() + yz * v.y() + zz * v.z()};
    }
};

/// One body's side of a point correction at world offset r. With the body's principal axes e_k
/// (world) and inverse moments d_k, I⁻¹ = Σ d_k e_k e_kᵀ, so −[r]× I⁻¹ [r]× = Σ d_k c_k c_kᵀ
/// with c_k = e_k × r, and the turn for an impulse p is I⁻¹ (r × p) = Σ d_k (c_k · p) e_k:
/// three cross products and rank-one updates instead of 3 x 3 matrix products.
struct PointResponse {
    Vec3 axes[3];
    Vec3 arms[3];  ///< c_k = e_k × r
    Vec3 inverseMoments = Vec3::Zero();
    bool rotates = false;

    /// For `angular` the response is to an angular impulse: arms are the axes themselves
    /// (I⁻¹ = Σ d_k e_k e_kᵀ) and r is unused.
    PointResponse(const Body& body, const Vec3& r, bool angular = false)
        : PointResponse(body, body.q.toRotationMatrix(), r, angular) {}
    /// With the body's rotation matrix already at hand.
    PointResponse(const Body& body, const Mat3& rotation, const Vec3& r, bool angular = false) {
        rotates = body.rotates() && body.invMass > 0.0;
        if (!rotates) return;
        for (int k = 0; k < 3; ++k) {
            axes[k] = rotation.col(k);
            arms[k] = angular ? axes[k] : axes[k].cross(r);
        }
        inverseMoments = body.invInertia;
    }
    void addTo(Symmetric3& m) const {
        if (!rotates) return;
        for (int k = 0; k < 3; ++k) {
            const Vec3& c = arms[k];
            const double d = inverseMoments[k];
            const Vec3 dc = d * c;
            m.xx += dc.x() * c.x();
            m.yy += dc.y() * c.y();
            m.zz += dc.z() * c.z();
            m.xy += dc.x() * c.y();
            m.xz += dc.x() * c.z();
            m.yz += dc.y() * c.z();
        }
    }
    Vec3 turn(const Vec3& p) const {
        if (!rotates) return Vec3::Zero();
        return axes[0] * (inverseMoments[0] * arms[0].dot(p)) +
               axes[1] * (inverseMoments[1] * arms[1].dot(p)) +
               axes[2] * (inverseMoments[2] * arms[2].dot(p));
    }
};

/// Solves m x = b by cofactors; false when m is singular (both bodies static).
inline bool solveSymmetric(const Symmetric3& m, const Vec3& b, Vec3& x) {
    const double c00 = m.yy * m.zz - m.yz * m.yz;
    const double c01 = m.xz * m.yz - m.xy * m.zz;
    const double c02 = m.xy * m.yz - m.xz * m.yy;
    const double determinant = m.xx * c00 + m.xy * c01 + m.xz * c02;
    if (!(std::abs(determinant) > 1e-300) || !std::isfinite(determinant)) return false;
    const double c11 = m.xx * m.zz - m.xz * m.xz;
    const double c12 = m.xy * m.xz - m.xx * m.yz;
    const double c22 = m.xx * m.yy - m.xy * m.xy;
    const double inv = 1.0 / determinant;
    x = Vec3(c00 * b.x() + c01 * b.y() + c02 * b.z(), c01 * b.x() + c11 * b.y() + c12 * b.z(),
             c02 * b.x() + c12 * b.y() + c22 * b.z()) *
        inv;
    return true;
}

}  // namespace

namespace {

/// The point correction once both sides' responses are known (applyPointCorrection).
Vec3 solvePoint(SolverContext& ctx, uint32_t i0, uint32_t i1, const Vec3& delta,
                const PointResponse& s0, const PointResponse& s1, double compliance, Vec3& lambda) {
    if (ctx.repairDistance > 0.0 &&  // the norm only matters while repairing
        skippedByRepair(ctx, delta.norm(), ctx.repairDistance, compliance))
        return Vec3::Zero();
    const Body& b0 = ctx.bodies[i0];
    const Body& b1 = ctx.bodies[i1];
    // K = Σ (1/m) 1 − [r]× I⁻¹ [r]×: the generalised inverse masses of Eq. 2 and Eq. 3 for
    // every direction at once (nᵀ K n = w1 + w2).
    const double alphaTilde = compliance * ctx.invH2;
    const double diagonal = b0.invMass + b1.invMass + alphaTilde;
    Symmetric3 k{.xx = diagonal, .yy = diagonal, .zz = diagonal};
    s0.addTo(k);
    s1.addTo(k);
    Vec3 deltaLambda;
    if (!solveSymmetric(k, delta - alphaTilde * lambda, deltaLambda))  // Eq. 4, vector form
        return Vec3::Zero();                                           // two static bodies
    lambda += deltaLambda;                                                // Eq. 5, vector form
    moveBody(ctx, i0, deltaLambda * b0.invMass, s0.turn(deltaLambda));    // Eq. 6, Eq. 8
    moveBody(ctx, i1, -deltaLambda * b1.invMass, -s1.turn(deltaLambda));  // Eq. 7, Eq. 9
    return deltaLambda;
}

}  // namespace

Vec3 applyPointCorrection(SolverContext& ctx, uint32_t i0, uint32_t i1, const Vec3& delta,
                          const Vec3& r0, const Vec3& r1, double compliance, Vec3& lambda) {
    return solvePoint(ctx, i0, i1, delta, PointResponse(ctx.bodies[i0], r0),
                      PointResponse(ctx.bodies[i1], r1), compliance, lambda);
}

Vec3 applyAttachmentCorrection(SolverContext& ctx, uint32_t i0, uint32_t i1,
                               const Vec3& anchor0, const Vec3& anchor1, double compliance,
                               Vec3& lambda) {
    const Body& b0 = ctx.bodies[i0];
    const Body& b1 = ctx.bodies[i1];
    if (ctx.projection == JointProjection::Start) {
        // The violation on the current poses, the Jacobian (lever arms, inverse inertias) on the
        // substep's start: the SHAKE form, which keeps a pendulum's energy.
        const Vec3 delta = (b1.x + b1.q * anchor1) - (b0.x + b0.q * anchor0);
        const Mat3 start0 = directionOrientation(ctx, b0).toRotationMatrix();
        const Mat3 start1 = directionOrientation(ctx, b1).toRotationMatrix();
        return solvePoint(ctx, i0, i1, delta, PointResponse(b0, start0, start0 * anchor0),
                          PointResponse(b1, start1, start1 * anchor1), compliance, lambda);
    }
    // One rotation matrix per body serves both the anchors and the inverse mass.
    const Mat3 rotation0 = b0.q.toRotationMatrix();
    const Mat3 rotation1 = b1.q.toRotationMatrix();
    const Vec3 r0 = rotation0 * anchor0;
    const Vec3 r1 = rotation1 * anchor1;
    const Vec3 delta = (b1.x + r1) - (b0.x + r0);
    return solvePoint(ctx, i0, i1, delta, PointResponse(b0, rotation0, r0),
                      PointResponse(b1, rotation1, r1), compliance, lambda);
}

Vec3 applyRotationCorrection(SolverContext& ctx, uint32_t i0, uint32_t i1, const Vec3& rotation,
                             double compliance, Vec3& lambda, const Vec3* freeAxis) {
    if (ctx.repairAngle > 0.0 && skippedByRepair(ctx, rotation.norm(), ctx.repairAngle, compliance))
        return Vec3::Zero();
    const Body& b0 = ctx.bodies[i0];
    const Body& b1 = ctx.bodies[i1];
    // K = I0⁻¹ + I1⁻¹ in world coordinates, each Σ d_k e_k e_kᵀ over the principal axes
    // (nᵀ K n is Eq. 11 plus Eq. 12).
    const PointResponse s0(b0, directionOrientation(ctx, b0).toRotationMatrix(), Vec3::Zero(),
                           /*angular=*/true);
    const PointResponse s1(b1, directionOrientation(ctx, b1).toRotationMatrix(), Vec3::Zero(),
                           /*angular=*/true);
    const double alphaTilde = compliance * ctx.invH2;
    Symmetric3 k{.xx = alphaTilde, .yy = alphaTilde, .zz = alphaTilde};
    s0.addTo(k);
    s1.addTo(k);
    const Vec3 rhs = rotation - alphaTilde * lambda;  // Eq. 13's numerator, vector form
    Vec3 deltaLambda;
    if (freeAxis) {
        // Only the two directions normal to the free axis are constrained: solve K restricted
        // to that plane, so the correction leaves the rotation about the axis alone.
        const Vec3 u = anyPerpendicular(*freeAxis);
        const Vec3 v = freeAxis->cross(u);
        const Vec3 ku = k.times(u);
        const Vec3 kv = k.times(v);
        const double a = u.dot(ku), b = u.dot(kv), d = v.dot(kv);
        const double determinant = a * d - b * b;
        if (!(determinant > 1e-300) || !std::isfinite(determinant)) return Vec3::Zero();
        const double ru = u.dot(rhs), rv = v.dot(rhs);
        deltaLambda = u * ((d * ru - b * rv) / determinant) + v * ((a * rv - b * ru) / determinant);
    } else if (!solveSymmetric(k, rhs, deltaLambda)) {
        return Vec3::Zero();  // two static bodies
    }
    lambda += deltaLambda;                                   // Eq. 14, vector form
    moveBody(ctx, i0, Vec3::Zero(), s0.turn(deltaLambda));   // Eq. 15
    moveBody(ctx, i1, Vec3::Zero(), -s1.turn(deltaLambda));  // Eq. 16
    return deltaLambda;
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
    const double magnitude = deltaOmega.norm();
    if (!(magnitude > kDirectionEpsilon)) return Vec3::Zero();
    const Vec3 n = deltaOmega / magnitude;
    const double w = b0.angularInverseMass(n) + b1.angularInverseMass(n);
    if (!(w > 0.0)) return Vec3::Zero();
    const Vec3 p = deltaOmega / w;  // Eq. 33's angular form, with Eq. 11 and Eq. 12 for w
    if (b0.rotates() && b0.invMass > 0.0) b0.omega += b0.applyInverseInertia(p);
    if (b1.rotates() && b1.invMass > 0.0) b1.omega -= b1.applyInverseInertia(p);
    return p;
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
