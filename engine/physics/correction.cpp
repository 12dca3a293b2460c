#include "physics/correction.h"

namespace substep {
namespace {

/// One body's side of a correction along a unit direction: its generalised inverse mass and
/// the rotation per unit multiplier, computed once and used for both (Eqs. 2-3, 8-9, 11-12).
struct BodyResponse {
    double w = 0.0;                ///< generalised inverse mass
    Vec3 rotationPerUnit = Vec3::Zero();  ///< world rotation per unit Δλ: I⁻¹ (r × n) or I⁻¹ n
};

/// Response to a positional correction along n at world offset r.
inline BodyResponse positionalResponse(const Body& body, const Vec3& r, const Vec3& n) {
    if (body.invMass == 0.0) return {};
    if (!body.rotates()) return {body.invMass, Vec3::Zero()};
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

/// Moves body `index` by its share of a correction with multiplier step `deltaLambda` along n
/// (sign +1 for body 0, −1 for body 1): Eqs. 6-9 and 15-16, or gathered for Jacobi.
inline void applyCorrection(SolverContext& ctx, uint32_t index, const BodyResponse& response,
                            const Vec3& dx, double deltaLambda) {
    Body& body = ctx.bodies[index];
    if (body.invMass == 0.0) return;
    const Vec3 dtheta = response.rotationPerUnit * deltaLambda;
    if (ctx.solver == SolverType::Jacobi) {
        JacobiDelta& d = ctx.deltas[index];
        d.position += dx;
        d.rotation += dtheta;
        ++d.count;
        return;
    }
    body.x += dx;
    if (body.rotates()) addRotation(body.q, dtheta);
}

}  // namespace

Vec3 applyPositionalCorrection(SolverContext& ctx, uint32_t i0, uint32_t i1, const Vec3& delta,
                               const Vec3& r0, const Vec3& r1, double compliance, double& lambda) {
    const double c = delta.norm();
    // A zero correction has no direction; there is nothing to do (and no NaN to make).
    if (!(c > kDirectionEpsilon)) return Vec3::Zero();
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
    lambda += deltaLambda;  // Eq. 5
    const Vec3 p = deltaLambda * n;
    applyCorrection(ctx, i0, s0, p * b0.invMass, deltaLambda);
    applyCorrection(ctx, i1, s1, -p * b1.invMass, -deltaLambda);
    return p;
}

Vec3 applyAngularCorrection(SolverContext& ctx, uint32_t i0, uint32_t i1, const Vec3& rotation,
                            double compliance, double& lambda) {
    const double theta = rotation.norm();
    if (!(theta > kDirectionEpsilon)) return Vec3::Zero();
    const Vec3 n = rotation / theta;
    const BodyResponse s0 = angularResponse(ctx.bodies[i0], n);  // Eq. 11
    const BodyResponse s1 = angularResponse(ctx.bodies[i1], n);  // Eq. 12
    const double alphaTilde = compliance * ctx.invH2;
    const double denominator = s0.w + s1.w + alphaTilde;
    if (!(denominator > 0.0)) return Vec3::Zero();
    const double deltaLambda = (theta - alphaTilde * lambda) / denominator;  // Eq. 13
    lambda += deltaLambda;                                                  // Eq. 14
    applyCorrection(ctx, i0, s0, Vec3::Zero(), deltaLambda);
    applyCorrection(ctx, i1, s1, Vec3::Zero(), -deltaLambda);
    return deltaLambda * n;
}

Vec3 applyVelocityCorrection(Body& b0, Body& b1, const Vec3& deltaVelocity, const Vec3& r0,
                             const Vec3& r1) {
    const double magnitude = deltaVelocity.norm();
    if (!(magnitude > kDirectionEpsilon)) return Vec3::Zero();
    const Vec3 n = deltaVelocity / magnitude;
    const double w = b0.positionalInverseMass(r0, n) + b1.positionalInverseMass(r1, n);
    if (!(w > 0.0)) return Vec3::Zero();
    const Vec3 p = deltaVelocity / w;  // Eq. 33
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
    const Vec3 p = deltaOmega / w;
    if (b0.rotates() && b0.invMass > 0.0) b0.omega += b0.applyInverseInertia(p);
    if (b1.rotates() && b1.invMass > 0.0) b1.omega -= b1.applyInverseInertia(p);
    return p;
}

void applyJacobiDeltas(Body* bodies, JacobiDelta* deltas, size_t count) {
    for (size_t i = 0; i < count; ++i) {
        JacobiDelta& d = deltas[i];
        if (d.count == 0) continue;
        // Averaging over the body's corrections keeps Jacobi from overshooting where several
        // constraints push the same body the same way.
        const double share = 1.0 / static_cast<double>(d.count);
        bodies[i].x += d.position * share;
        if (bodies[i].rotates()) addRotation(bodies[i].q, d.rotation * share);
        d = JacobiDelta{};
    }
}

}  // namespace substep
