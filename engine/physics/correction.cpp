#include "physics/correction.h"

namespace substep {
namespace {

/// Moves one body by the positional impulse p at world offset r (sign +1 for body 0, −1 for
/// body 1): Eqs. 6-9, or gathered for a Jacobi iteration.
inline void applyPositionalImpulse(SolverContext& ctx, uint32_t index, const Vec3& p,
                                   const Vec3& r) {
    Body& body = ctx.bodies[index];
    if (body.invMass == 0.0) return;
    const Vec3 dx = p * body.invMass;
    const Vec3 dtheta = body.rotates() ? body.applyInverseInertia(r.cross(p)) : Vec3::Zero();
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

/// Turns one body by the angular impulse p: Eqs. 15-16, or gathered for Jacobi.
inline void applyAngularImpulse(SolverContext& ctx, uint32_t index, const Vec3& p) {
    Body& body = ctx.bodies[index];
    if (!body.rotates() || body.invMass == 0.0) return;
    const Vec3 dtheta = body.applyInverseInertia(p);
    if (ctx.solver == SolverType::Jacobi) {
        JacobiDelta& d = ctx.deltas[index];
        d.rotation += dtheta;
        ++d.count;
        return;
    }
    addRotation(body.q, dtheta);
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
    const double w0 = b0.positionalInverseMass(r0, n);  // Eq. 2
    const double w1 = b1.positionalInverseMass(r1, n);  // Eq. 3
    const double alphaTilde = compliance * ctx.invH2;
    const double denominator = w0 + w1 + alphaTilde;
    if (!(denominator > 0.0)) return Vec3::Zero();  // two static bodies
    // Eq. 4 with ERRATA item 1's sign: λ grows with the stretch c, so f = λ n / h² (Eq. 10).
    const double deltaLambda = (c - alphaTilde * lambda) / denominator;
    lambda += deltaLambda;  // Eq. 5
    const Vec3 p = deltaLambda * n;
    applyPositionalImpulse(ctx, i0, p, r0);
    applyPositionalImpulse(ctx, i1, -p, r1);
    return p;
}

Vec3 applyAngularCorrection(SolverContext& ctx, uint32_t i0, uint32_t i1, const Vec3& rotation,
                            double compliance, double& lambda) {
    const double theta = rotation.norm();
    if (!(theta > kDirectionEpsilon)) return Vec3::Zero();
    const Vec3 n = rotation / theta;
    const double w0 = ctx.bodies[i0].angularInverseMass(n);  // Eq. 11
    const double w1 = ctx.bodies[i1].angularInverseMass(n);  // Eq. 12
    const double alphaTilde = compliance * ctx.invH2;
    const double denominator = w0 + w1 + alphaTilde;
    if (!(denominator > 0.0)) return Vec3::Zero();
    const double deltaLambda = (theta - alphaTilde * lambda) / denominator;  // Eq. 13
    lambda += deltaLambda;                                                  // Eq. 14
    const Vec3 p = deltaLambda * n;
    applyAngularImpulse(ctx, i0, p);
    applyAngularImpulse(ctx, i1, -p);
    return p;
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
