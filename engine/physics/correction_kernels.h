#pragma once
/// The inner steps of the correction operations (correction.h), inline: a joint's parts call
/// them several times per joint and substep, each waiting on the previous one's turn of a shared
/// body, and inlined into the joint the matrices, lever arms and turned quaternions stay in
/// registers instead of going through memory to a call. correction.cpp defines the operations of
/// correction.h with these; the spherical joint's limits and attachment (a rope's links) and the
/// joint damping (joint_solver.cpp) call them directly. One implementation, so both give the
/// same bytes.

#include "physics/correction.h"
#include "physics/gyroscopic_step.h"

#include <cmath>

namespace substep::correction_kernels {

/// Turns the unit quaternion q by the world rotation vector θ exactly, as integrateRotation does,
/// but shorter on the solver's critical path (each correction's turn of a body is what the next
/// constraint on that body waits for): q ← cos φ q + (sin φ / φ) (0, θ/2) q with φ = |θ|/2, by
/// their Taylor series in φ² (through φ⁸: the remainder is below 3e-17 for φ² < 0.01), without
/// integrateRotation's square root and division. Both terms are orthogonal with norms cos φ and
/// sin φ, so q stays unit to rounding; World::integrate normalises it again every substep, so
/// rounding cannot accumulate over substeps. Larger turns (beyond 0.2 rad) take integrateRotation.
[[gnu::always_inline]] inline void turnQuaternion(Quat& q, const Vec3& rotation) {
    const double x = 0.25 * rotation.squaredNorm();  // φ²
    if (!(x < 0.01)) {
        integrateRotation(q, rotation);
        return;
    }
    // The series grouped in pairs (Estrin's scheme) so that their latency is a few products.
    const double x2 = x * x;
    const double cosine = (1.0 - 0.5 * x) + x2 * ((1.0 / 24 - x * (1.0 / 720)) + x2 * (1.0 / 40320));
    const double sinc = (1.0 - x * (1.0 / 6)) + x2 * ((1.0 / 120 - x * (1.0 / 5040)) + x2 * (1.0 / 362880));
    const Quat product = Quat(0.0, rotation.x(), rotation.y(), rotation.z()) * q;
    q.coeffs() = cosine * q.coeffs() + (0.5 * sinc) * product.coeffs();
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
    if (body.rotates()) turnQuaternion(body.q, dtheta);
}

/// Whether a correction turns the body: a dynamic rigid body (particles and static bodies do not).
inline bool turns(const Body& body) { return body.rotates() && body.invMass > 0.0; }

/// Turns body `index` by dtheta alone (the rotation of Eq. 8, Eq. 9, Eq. 15 or Eq. 16), or
/// gathers it for Jacobi: moveBody without a translation to add.
[[gnu::always_inline]] inline void turnBody(SolverContext& ctx, uint32_t index, const Vec3& dtheta) {
    if (ctx.solver == SolverType::Jacobi) {
        JacobiDelta& d = ctx.deltas[index];
        d.rotation += dtheta;
        ++d.count;
        return;
    }
    turnQuaternion(ctx.bodies[index].q, dtheta);
}

/// A symmetric 3 x 3 matrix by its six entries (the point and rotation corrections' K).
struct Symmetric3 {
    double xx = 0, yy = 0, zz = 0, xy = 0, xz = 0, yz = 0;
    /// Adds d c cᵀ.
    void addRankOne(double d, const Vec3& c) {
        const double dx = d * c.x(), dy = d * c.y(), dz = d * c.z();
        xx += dx * c.x();
        yy += dy * c.y();
        zz += dz * c.z();
        xy += dx * c.y();
        xz += dx * c.z();
        yz += dy * c.z();
    }
    /// Adds d (|r|² 1 − r rᵀ) = −d [r]× [r]×.
    void addCrossSquare(double d, const Vec3& r) {
        const double dx = d * r.x(), dy = d * r.y(), dz = d * r.z();
        xx += dy * r.y() + dz * r.z();
        yy += dx * r.x() + dz * r.z();
        zz += dx * r.x() + dy * r.y();
        xy -= dx * r.y();
        xz -= dx * r.z();
        yz -= dy * r.z();
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

/// A turning body's world inverse inertia I⁻¹ = R diag(d) Rᵀ = Σ d_k e_k e_kᵀ (e_k the
/// columns of R, its principal axes) split as d_j 1 + Σ_{k≠j} (d_k − d_j) e_k e_kᵀ: an isotropic
/// part and one rank-one term per principal axis whose moment differs from d_j. With j one of
/// two equal moments (a box of square section, a capsule, a cylinder) a single term is left,
/// with three (a sphere, a cube) none, and with three different moments two instead of three:
/// each correction's K and turn cost that many rank-one updates and products fewer.
struct InverseInertia {
    double isotropic = 0.0;  ///< d_j
    int count = 0;           ///< rank-one terms
    Vec3 axes[2];            ///< their principal axes e_k (world)
    double excess[2];        ///< d_k − d_j

    InverseInertia() = default;  // a body that does not turn: never read
    /// From the matrix whose columns are the body's principal axes.
    InverseInertia(const Body& body, const Mat3& rotation) {
        split(body.invInertia, [&](int k) -> Vec3 { return rotation.col(k); });
    }
    /// From the orientation itself: only the columns of its matrix that a rank-one term needs
    /// (principalAxis, the same numbers as toRotationMatrix's columns), so a capsule or a rod
    /// of square section builds one column, a cube or a sphere none.
    InverseInertia(const Body& body, const Quat& orientation) {
        split(body.invInertia, [&](int k) { return principalAxis(orientation, k); });
    }
    /// I⁻¹ v.
    Vec3 times(const Vec3& v) const {
        Vec3 result = isotropic * v;
        for (int t = 0; t < count; ++t) result += (excess[t] * axes[t].dot(v)) * axes[t];
        return result;
    }
    /// vᵀ I⁻¹ v.
    double quadratic(const Vec3& v) const {
        double result = isotropic * v.squaredNorm();
        for (int t = 0; t < count; ++t) result += excess[t] * square(axes[t].dot(v));
        return result;
    }
    /// Adds I⁻¹ to m.
    void addTo(Symmetric3& m) const {
        m.xx += isotropic;
        m.yy += isotropic;
        m.zz += isotropic;
        for (int t = 0; t < count; ++t) m.addRankOne(excess[t], axes[t]);
    }
    /// Adds −[r]× I⁻¹ [r]× to m, the body's part of a point correction's K at offset r: the
    /// isotropic part gives d_j (|r|² 1 − r rᵀ), each axis (d_k − d_j) c cᵀ with c = e_k × r.
    void addPointTo(Symmetric3& m, const Vec3& r) const {
        m.addCrossSquare(isotropic, r);
        for (int t = 0; t < count; ++t) m.addRankOne(excess[t], axes[t].cross(r));
    }

private:
    static double square(double x) { return x * x; }
    /// j is a moment another one shares, where there is one (d_y = d_z: j = 1, else j = 0);
    /// a term for each other axis whose moment differs from d_j. Written out rather than
    /// looped, so that the struct is filled in place without a loop's bookkeeping.
    template <typename Column>
    void split(const Vec3& d, const Column& column) {
        if (d.y() == d.z()) {
            isotropic = d.y();
            if (d.x() != isotropic) add(column(0), d.x());
        } else {
            isotropic = d.x();
            if (d.y() != isotropic) add(column(1), d.y());
            if (d.z() != isotropic) add(column(2), d.z());
        }
    }
    void add(const Vec3& axis, double moment) {
        axes[count] = axis;
        excess[count] = moment - isotropic;
        ++count;
    }
};

/// Both bodies' sides of a correction: whether each turns and, where it does, its world inverse
/// inertia from its current orientation (a rotation matrix or the quaternion itself). Static
/// bodies and particles have none.
struct PairInertia {
    bool turns0, turns1;
    InverseInertia inverse0, inverse1;

    template <class Orientation>
    [[gnu::always_inline]] PairInertia(const Body& b0, const Body& b1, const Orientation& orientation0,
                                       const Orientation& orientation1)
        : turns0(turns(b0)),
          turns1(turns(b1)),
          inverse0(turns0 ? InverseInertia(b0, orientation0) : InverseInertia()),
          inverse1(turns1 ? InverseInertia(b1, orientation1) : InverseInertia()) {}
};

/// applyPointCorrection's body.
[[gnu::always_inline]] inline Vec3 pointCorrection(SolverContext& ctx, uint32_t i0, uint32_t i1,
                                                   const Mat3& rotation0, const Mat3& rotation1,
                                                   const Vec3& delta, const Vec3& r0, const Vec3& r1,
                                                   double compliance, Vec3& lambda) {
    if (ctx.repairDistance > 0.0 &&  // the norm only matters while repairing
        skippedByRepair(ctx, delta.norm(), ctx.repairDistance, compliance))
        return Vec3::Zero();
    Body& b0 = ctx.bodies[i0];
    Body& b1 = ctx.bodies[i1];
    // K = Σ (1/m) 1 − [r]× I⁻¹ [r]×: the generalised inverse masses of Eq. 2 and Eq. 3 for
    // every direction at once (nᵀ K n = w1 + w2).
    const double alphaTilde = compliance * ctx.invH2;
    const double diagonal = b0.invMass + b1.invMass + alphaTilde;
    Symmetric3 k{.xx = diagonal, .yy = diagonal, .zz = diagonal};
    const auto [turns0, turns1, inverse0, inverse1] = PairInertia(b0, b1, rotation0, rotation1);
    if (turns0) inverse0.addPointTo(k, r0);
    if (turns1) inverse1.addPointTo(k, r1);
    Vec3 deltaLambda;
    if (!solveSymmetric(k, delta - alphaTilde * lambda, deltaLambda))  // Eq. 4, vector form
        return Vec3::Zero();                                           // two static bodies
    lambda += deltaLambda;                                             // Eq. 5, vector form
    // Eq. 6 and Eq. 8 for body 0, Eq. 7 and Eq. 9 for body 1.
    const Vec3 turn0 = turns0 ? inverse0.times(r0.cross(deltaLambda)) : Vec3::Zero();
    const Vec3 turn1 = turns1 ? inverse1.times(r1.cross(deltaLambda)) : Vec3::Zero();
    if (ctx.solver == SolverType::Jacobi) {
        moveBody(ctx, i0, deltaLambda * b0.invMass, turn0);
        moveBody(ctx, i1, -deltaLambda * b1.invMass, -turn1);
        return deltaLambda;
    }
    if (b0.invMass > 0.0) b0.x += deltaLambda * b0.invMass;
    if (b1.invMass > 0.0) b1.x -= deltaLambda * b1.invMass;
    if (turns0) turnQuaternion(b0.q, turn0);
    if (turns1) turnQuaternion(b1.q, -turn1);
    return deltaLambda;
}


/// applyAttachmentCorrection's body.
[[gnu::always_inline]] inline Vec3 attachmentCorrection(SolverContext& ctx, uint32_t i0, uint32_t i1,
                                                        const Vec3& anchor0, const Vec3& anchor1,
                                                        double compliance, Vec3& lambda) {
    const Body& b0 = ctx.bodies[i0];
    const Body& b1 = ctx.bodies[i1];
    // One rotation matrix per body serves both the anchors and the inverse mass.
    const Mat3 rotation0 = b0.q.toRotationMatrix();
    const Mat3 rotation1 = b1.q.toRotationMatrix();
    const Vec3 r0 = rotation0 * anchor0;
    const Vec3 r1 = rotation1 * anchor1;
    const Vec3 delta = (b1.x + r1) - (b0.x + r0);
    if (ctx.projection == JointProjection::Start) {
        // The violation on the current poses, the Jacobian (lever arms, inverse inertias) on the
        // substep's start: the SHAKE form, which keeps a pendulum's energy.
        const Mat3 start0 = directionRotation(ctx, b0, rotation0);
        const Mat3 start1 = directionRotation(ctx, b1, rotation1);
        return applyPointCorrection(ctx, i0, i1, start0, start1, delta, start0 * anchor0, start1 * anchor1,
                                    compliance, lambda);
    }
    return pointCorrection(ctx, i0, i1, rotation0, rotation1, delta, r0, r1, compliance, lambda);
}

/// applyAngularCorrection about a unit axis n by the angle θ ≥ 0 (Eqs. 11-16): the form an
/// angle limit takes, whose axis is already unit and whose excess is the angle, so that it does
/// not build the rotation vector θ n only to take its length and divide by it again (a square
/// root and a division on the joint's critical path).
[[gnu::always_inline]] inline Vec3 axisCorrection(SolverContext& ctx, uint32_t i0, uint32_t i1, const Mat3& rotation0,
                                                  const Mat3& rotation1, const Vec3& n, double theta,
                                                  double compliance, double& lambda, double lambdaLimit = kUnlimited) {
    if (!(theta > kDirectionEpsilon)) return Vec3::Zero();
    if (skippedByRepair(ctx, theta, ctx.repairAngle, compliance)) return Vec3::Zero();
    const Body& b0 = ctx.bodies[i0];
    const Body& b1 = ctx.bodies[i1];
    const auto [turns0, turns1, inverse0, inverse1] = PairInertia(b0, b1, rotation0, rotation1);
    const double alphaTilde = compliance * ctx.invH2;
    double denominator = alphaTilde;
    if (turns0) denominator += inverse0.quadratic(n);  // Eq. 11
    if (turns1) denominator += inverse1.quadratic(n);  // Eq. 12
    if (!(denominator > 0.0)) return Vec3::Zero();
    // Eq. 13 with ERRATA item 1's sign (θ rather than −θ).
    const double deltaLambda = (theta - alphaTilde * lambda) / denominator;
    if (lambda + deltaLambda > lambdaLimit) return Vec3::Zero();
    lambda += deltaLambda;                                                  // Eq. 14
    const Vec3 p = deltaLambda * n;
    if (turns0) turnBody(ctx, i0, inverse0.times(p));                        // Eq. 15
    if (turns1) turnBody(ctx, i1, -inverse1.times(p));                       // Eq. 16
    return p;
}

/// applyAngularCorrection's body (with the matrices of the bodies' current orientations): the
/// rotation vector's length and direction, then axisCorrection.
[[gnu::always_inline]] inline Vec3 angularCorrection(SolverContext& ctx, uint32_t i0, uint32_t i1,
                                                     const Mat3& rotation0, const Mat3& rotation1,
                                                     const Vec3& rotation, double compliance, double& lambda,
                                                     double lambdaLimit = kUnlimited) {
    const double theta = rotation.norm();
    if (!(theta > kDirectionEpsilon)) return Vec3::Zero();
    return axisCorrection(ctx, i0, i1, rotation0, rotation1, rotation / theta, theta, compliance, lambda, lambdaLimit);
}

/// applyRotationCorrection's body (with the matrices of the orientations directionOrientation
/// names).
[[gnu::always_inline]] inline Vec3 rotationCorrection(SolverContext& ctx, uint32_t i0, uint32_t i1,
                                                      const Mat3& rotation0, const Mat3& rotation1,
                                                      const Vec3& rotation, double compliance, Vec3& lambda,
                                                      const Vec3* freeAxis = nullptr) {
    if (ctx.repairAngle > 0.0 && skippedByRepair(ctx, rotation.norm(), ctx.repairAngle, compliance))
        return Vec3::Zero();
    const Body& b0 = ctx.bodies[i0];
    const Body& b1 = ctx.bodies[i1];
    const auto [turns0, turns1, inverse0, inverse1] = PairInertia(b0, b1, rotation0, rotation1);
    const double alphaTilde = compliance * ctx.invH2;
    const Vec3 rhs = rotation - alphaTilde * lambda;  // Eq. 13's numerator, vector form
    // K = I0⁻¹ + I1⁻¹ in world coordinates (nᵀ K n is Eq. 11 plus Eq. 12).
    Vec3 deltaLambda;
    if (freeAxis) {
        // Only the two directions normal to the free axis are constrained: K restricted to that
        // plane, a 2 x 2 system, so the correction leaves the rotation about the axis alone. The
        // plane's basis u = axis × helper, v = axis × u need not be unit (the solution
        // P (Pᵀ K P)⁻¹ Pᵀ rhs does not depend on the basis P = [u v]); u ⊥ v keeps the
        // isotropic part on the diagonal. No square root or division then waits on the axis.
        const Vec3& axis = *freeAxis;
        const bool helperX = axis.x() * axis.x() < 0.3249 * axis.squaredNorm();  // |x| < 0.57 |axis|
        const Vec3 u = axis.cross(helperX ? Vec3::UnitX() : Vec3::UnitY());
        const Vec3 v = axis.cross(u);
        const double uu = u.squaredNorm(), vv = v.squaredNorm();
        double diagonal = alphaTilde, a = 0.0, b = 0.0, d = 0.0;
        for (const InverseInertia* inverse : {turns0 ? &inverse0 : nullptr, turns1 ? &inverse1 : nullptr}) {
            if (!inverse) continue;
            // uᵀ I⁻¹ u, uᵀ I⁻¹ v and vᵀ I⁻¹ v: the isotropic part adds |u|², 0 and |v|².
            diagonal += inverse->isotropic;
            for (int t = 0; t < inverse->count; ++t) {
                const double eu = inverse->axes[t].dot(u), ev = inverse->axes[t].dot(v);
                a += inverse->excess[t] * eu * eu;
                b += inverse->excess[t] * eu * ev;
                d += inverse->excess[t] * ev * ev;
            }
        }
        a += diagonal * uu;
        d += diagonal * vv;
        const double determinant = a * d - b * b;
        if (!(determinant > 1e-300) || !std::isfinite(determinant)) return Vec3::Zero();
        const double ru = u.dot(rhs), rv = v.dot(rhs);
        const double inverseDeterminant = 1.0 / determinant;
        deltaLambda = u * ((d * ru - b * rv) * inverseDeterminant) + v * ((a * rv - b * ru) * inverseDeterminant);
    } else {
        Symmetric3 k{.xx = alphaTilde, .yy = alphaTilde, .zz = alphaTilde};
        if (turns0) inverse0.addTo(k);
        if (turns1) inverse1.addTo(k);
        if (!solveSymmetric(k, rhs, deltaLambda)) return Vec3::Zero();  // two static bodies
    }
    lambda += deltaLambda;                                          // Eq. 14, vector form
    if (turns0) turnBody(ctx, i0, inverse0.times(deltaLambda));     // Eq. 15
    if (turns1) turnBody(ctx, i1, -inverse1.times(deltaLambda));    // Eq. 16
    return deltaLambda;
}

/// applyAngularVelocityCorrection's body (the joint damping of Eq. 32, which runs along a chain).
[[gnu::always_inline]] inline Vec3 angularVelocityCorrection(Body& b0, Body& b1, const Vec3& deltaOmega) {
    const double magnitude = deltaOmega.norm();
    if (!(magnitude > kDirectionEpsilon)) return Vec3::Zero();
    const Vec3 n = deltaOmega / magnitude;
    // Each turning body's inverse inertia, from the columns of its rotation matrix it needs,
    // serves both w and the change of ω (Body::angularInverseMass and applyInverseInertia
    // would rotate n and p twice each).
    const auto [turns0, turns1, inverse0, inverse1] = PairInertia(b0, b1, b0.q, b1.q);
    double w = 0.0;
    if (turns0) w += inverse0.quadratic(n);
    if (turns1) w += inverse1.quadratic(n);
    if (!(w > 0.0)) return Vec3::Zero();
    const Vec3 p = deltaOmega / w;  // Eq. 33's angular form, with Eq. 11 and Eq. 12 for w
    if (turns0) b0.omega += inverse0.times(p);
    if (turns1) b1.omega -= inverse1.times(p);
    return p;
}

}  // namespace substep::correction_kernels
