#include "physics/contact.h"

#include "physics/contact_kinematics.h"
#include "physics/contact_patch.h"

#include <algorithm>
#include <cmath>

namespace substep {

using namespace contact_detail;  // the helpers contact.cpp and contact_patch.cpp share

namespace {

/// One body's side of a point correction along unit n at world offset r (Eq. 2 or Eq. 3, and
/// the rotation Eq. 8 or Eq. 9 makes per unit multiplier): what applyPositionalCorrection
/// computes, without its normalisation of a direction that is already unit. Always inlined:
/// the compiler kept it out of line, a call per body and direction (4 % of spheres1000).
struct PointResponse {
    double w = 0.0;
    Vec3 turn = Vec3::Zero();
};

[[gnu::always_inline]] inline PointResponse pointResponse(const Body& b, const Vec3& r, const Vec3& n) {
    if (b.invMass == 0.0) return {};
    if (!b.rotates()) return {b.invMass, Vec3::Zero()};
    const Vec3 rn = r.cross(n);
    if (b.isotropic) return {b.invMass + b.invInertia.x() * rn.squaredNorm(), b.invInertia.x() * rn};
    const Vec3 rnBody = b.q.conjugate() * rn;  // into the rest frame (paper 3.3.2)
    const Vec3 scaled = b.invInertia.cwiseProduct(rnBody);
    return {b.invMass + rnBody.dot(scaled), b.q * scaled};
}

/// Whether movePoint turns the body (its orientation, and so its lever arms, change).
inline bool turnsWhenMoved(const Body& b) { return b.invMass != 0.0 && b.rotates(); }

/// Eq. 6 to Eq. 9 for one body: moved by Δλ n / m and turned by Δλ I⁻¹ (r × n) (exactly, as
/// the correction operations turn). Gauss-Seidel only: Jacobi gathers through correction.cpp.
inline void movePoint(Body& b, const PointResponse& s, const Vec3& p, double deltaLambda) {
    if (b.invMass == 0.0) return;
    b.x += p * b.invMass;
    if (b.rotates()) integrateRotation(b.q, s.turn * deltaLambda);
}

/// The paper's contact for a pair with one point (a marble, a coin on its rim): the push
/// (Eq. 26), then static friction from the motion during the substep (Eq. 27, Eq. 28), each
/// the scalar update of Eq. 2 to Eq. 9. Fused: the normal is already unit, so the push skips
/// the general correction's normalisation, and both corrections move the bodies in place.
/// Jacobi takes applyPositionalCorrection, which gathers the motions instead.
///
/// In its four dependent steps: measure, push, measure the slip, hold it. contact_lanes.cpp
/// takes the same steps for up to four pairs at once, operation for operation (a pair gets the
/// same bits either way): a change here is a change there. The steps are flattened: GCC kept
/// Eigen's quaternion rotation out of line in them, a call per lever arm (8 % of spheres1000).
struct OnePointSolve {
    ContactPair& pair;
    Contact& c;
    Body& b0;
    Body& b1;
    SolverContext& ctx;
    bool active = true;  ///< steps are left to take
    Vec3 r0, r1;
    double depth = 0.0;
    Vec3 slip;
    double slipLength = 0.0;
    double lambdaTangent = 0.0;
    double limit = 0.0;

    OnePointSolve(ContactPair& p, Contact& contact, SolverContext& context)
        : pair(p), c(contact), b0(context.bodies[p.body0]), b1(context.bodies[p.body1]), ctx(context) {}

    bool gaussSeidel() const { return ctx.solver == SolverType::GaussSeidel; }

    /// Eq. 26: the points p1, p2 on the current poses and the depth d along n (with this
    /// file's normal, from body 1 towards body 0), to be pushed out as Δx = d n with α = 0.
    [[gnu::flatten]] void measure() {
        const Vec3& n = c.normal;
        r0 = b0.q * c.local0;
        r1 = b1.q * c.local1;
        depth = pushOut(((b1.x + r1) - (b0.x + r0)).dot(n), b0, b1, r0, r1, n, ctx);
        if (!(depth > kDirectionEpsilon)) {
            pair.lambdaNormal = c.lambdaNormal;
            active = false;
        }
    }

    /// The push, Eq. 2 to Eq. 9 with λ_n.
    [[gnu::flatten]] void push() {
        if (!active) return;
        const Vec3& n = c.normal;
        if (gaussSeidel()) {
            const PointResponse s0 = pointResponse(b0, r0, n);  // Eq. 2
            const PointResponse s1 = pointResponse(b1, r1, n);  // Eq. 3
            const double w = s0.w + s1.w;
            if (!(w > 0.0)) {
                pair.lambdaNormal = c.lambdaNormal;
                active = false;
                return;  // two static bodies
            }
            const double deltaLambda = depth / w;  // Eq. 4 with α = 0
            c.lambdaNormal += deltaLambda;          // Eq. 5
            const Vec3 p = deltaLambda * n;
            movePoint(b0, s0, p, deltaLambda);      // Eq. 6, Eq. 8
            movePoint(b1, s1, -p, -deltaLambda);    // Eq. 7, Eq. 9
        } else {
            applyPositionalCorrection(ctx, pair.body0, pair.body1, depth * n, r0, r1, 0.0, c.lambdaNormal);
        }
        pair.lambdaNormal = c.lambdaNormal;
        pair.anchored = false;
        if (!(pair.staticFriction > 0.0)) active = false;
    }

    /// Eq. 27 and Eq. 28: the slip, the motion of the contact during the substep across n.
    [[gnu::flatten]] void measureSlip() {
        if (!active) return;
        const Vec3& n = c.normal;
        // The lever arms on the pushed poses: only a body the push turned has a new one (a
        // static floor or wall keeps its own, and Jacobi turns no body before the gather).
        if (gaussSeidel() && turnsWhenMoved(b0)) r0 = b0.q * c.local0;
        if (gaussSeidel() && turnsWhenMoved(b1)) r1 = b1.q * c.local1;
        const Vec3 motion = (b0.x + r0 - previousPoint(b0, c.local0)) - (b1.x + r1 - previousPoint(b1, c.local1));  // Eq. 27
        slip = motion - motion.dot(n) * n;  // Eq. 28
        // A one-point pair keeps its λ_t in lambdaTangent1 alone (below), and hypot(x, 0) is
        // |x| exactly: no call to libm's hypot per pushing point (1 % of spheres1000's
        // instructions).
        lambdaTangent = pair.lambdaTangent2 == 0.0 ? std::abs(pair.lambdaTangent1) : pair.lambdaTangent();
        limit = pair.staticFriction * pair.lambdaNormal;
        if (gaussSeidel()) slipLength = slip.norm();
    }

    /// Static friction: Δx = Δp_t with α = 0, only while λ_t stays within μ_s λ_n (paper 3.5).
    [[gnu::flatten]] void holdSlip() {
        if (!active) return;
        if (gaussSeidel()) {
            if (slipLength > kDirectionEpsilon) {
                const Vec3 t = slip / -slipLength;  // the correction's direction, −Δp_t / |Δp_t|
                const PointResponse s0 = pointResponse(b0, r0, t);
                const PointResponse s1 = pointResponse(b1, r1, t);
                const double w = s0.w + s1.w;
                const double deltaLambda = slipLength / w;
                if (w > 0.0 && lambdaTangent + deltaLambda <= limit) {
                    lambdaTangent += deltaLambda;
                    const Vec3 p = deltaLambda * t;
                    movePoint(b0, s0, p, deltaLambda);
                    movePoint(b1, s1, -p, -deltaLambda);
                }
            }
        } else {
            applyPositionalCorrection(ctx, pair.body0, pair.body1, -slip, r0, r1, 0.0, lambdaTangent, limit);
        }
        pair.lambdaTangent1 = lambdaTangent;  // one point: the magnitude is all the readout needs
        pair.lambdaTangent2 = 0.0;
    }
};

void solveSinglePointPositions(ContactPair& pair, Contact& c, SolverContext& ctx) {
    OnePointSolve solve(pair, c, ctx);
    solve.measure();
    solve.push();
    solve.measureSlip();
    solve.holdSlip();
}

/// Eq. 33 along unit n for a velocity change of `change` along it, given both bodies' responses
/// along n at r0, r1: p = change n / (w1 + w2), then v and ω of both bodies.
inline void changePointVelocity(Body& b0, Body& b1, const PointResponse& s0, const PointResponse& s1,
                                const Vec3& n, double change) {
    const double w = s0.w + s1.w;
    if (!(w > 0.0)) return;
    const double impulse = change / w;
    if (b0.invMass > 0.0) {
        b0.v += (impulse * b0.invMass) * n;
        if (b0.rotates()) b0.omega += impulse * s0.turn;
    }
    if (b1.invMass > 0.0) {
        b1.v -= (impulse * b1.invMass) * n;
        if (b1.rotates()) b1.omega -= impulse * s1.turn;
    }
}

/// Dynamic friction of a one-point pair (Eq. 29, Eq. 30, Eq. 33), with the impulse clamped
/// (ERRATA item 2), after its normal velocity was set.
[[gnu::flatten]] void applySinglePointFriction(const ContactPair& pair, const Contact& c, Body& b0, Body& b1,
                              const Vec3& r0, const Vec3& r1, double h) {
    if (!(pair.dynamicFriction > 0.0)) return;
    const Vec3& n = c.normal;
    const Vec3 vAfter = pointVelocity(b0.v, b0.omega, r0) - pointVelocity(b1.v, b1.omega, r1);
    const Vec3 slip = vAfter - vAfter.dot(n) * n;  // Eq. 29: v_t
    const double slipSpeed = slip.norm();
    if (!(slipSpeed > kRestingSpeed)) return;
    const Vec3 t = slip / slipSpeed;
    const PointResponse s0 = pointResponse(b0, r0, t);
    const PointResponse s1 = pointResponse(b1, r1, t);
    // Eq. 30 with ERRATA item 2: an impulse of at most h μ_d f_n, f_n = λ_n / h² (Eq. 10),
    // changes the slip speed by at most that times w1 + w2; applied by Eq. 33.
    const double maxChange = pair.dynamicFriction * c.lambdaNormal / h * (s0.w + s1.w);
    changePointVelocity(b0, b1, s0, s1, t, -std::min(maxChange, slipSpeed));
}

/// After the collision pass: the approach a point of a one-point pair has left (its push's
/// velocity removed, a support under gravity approaches by g h) is removed, Eq. 34 with e = 0.
/// A point that collided and separates is left alone (its bounce). A point that did not
/// collide (a push between two bodies a collision reached) separates no faster than it did
/// before the substep (v̄_n, Eq. 29 on the velocities before the derivation): its own push is
/// gone, so a faster separation is what the other contacts' pushes of this substep gave it.
/// Left in, as it was, a frictionless pile never came to rest: spheres wedged between
/// neighbours were pushed apart by their supports at every substep, kept that as a real
/// separation, fell back into the overlap and were pushed apart again (the pile's energy rising
/// by up to 0.13 J in a frame, the pile chattering past 12 s).
void removeApproach(const Contact& c, Body& b0, Body& b1) {
    const Vec3& n = c.normal;
    const Vec3 r0 = b0.q * c.local0;
    const Vec3 r1 = b1.q * c.local1;
    const double vn = (pointVelocity(b0.v, b0.omega, r0) - pointVelocity(b1.v, b1.omega, r1)).dot(n);  // Eq. 29
    double target = std::max(vn, 0.0);
    if (!(c.restitutionImpulse > 0.0)) {
        const double vnBefore =
            (pointVelocity(b0.vPrev, b0.omegaPrev, r0) - pointVelocity(b1.vPrev, b1.omegaPrev, r1)).dot(n);
        target = std::min(target, std::max(vnBefore, 0.0));
    }
    if (std::abs(target - vn) > kRestingSpeed)
        changePointVelocity(b0, b1, pointResponse(b0, r0, n), pointResponse(b1, r1, n), n, target - vn);
}

/// The velocity pass for a pair with one point (Eq. 29, Eq. 30, Eq. 33, Eq. 34): restitution,
/// then dynamic friction with the impulse clamped (ERRATA item 2); after the collision pass,
/// removeApproach instead. Fused: each change is applied along its unit direction with the
/// generalised inverse mass computed once (the general Eq. 33 normalises the change and
/// computes w again). In its two dependent steps, which contact_lanes.cpp takes for up to four
/// pairs at once, operation for operation.
struct OnePointVelocities {
    const ContactPair& pair;
    const Contact& c;
    Body& b0;
    Body& b1;
    double h;
    double gravity;
    Vec3 r0, r1;
    bool friction = false;  ///< the normal step set the velocity: dynamic friction follows

    OnePointVelocities(const ContactPair& p, const Contact& contact, Body* bodies, double substep, double g)
        : pair(p), c(contact), b0(bodies[p.body0]), b1(bodies[p.body1]), h(substep), gravity(g) {}

    /// Eq. 34 (with Eq. 29 and Eq. 33), or removeApproach after the collision pass.
    [[gnu::flatten]] void normal() {
        if (c.collisionPass) {
            removeApproach(c, b0, b1);
            return;
        }
        if (!(c.lambdaNormal > 0.0)) return;
        const Vec3& n = c.normal;
        r0 = b0.q * c.local0;
        r1 = b1.q * c.local1;
        const Vec3 v = pointVelocity(b0.v, b0.omega, r0) - pointVelocity(b1.v, b1.omega, r1);  // Eq. 29
        const double vn = v.dot(n);                                                               // Eq. 29
        // v̄_n: Eq. 29 on the velocities before this substep's derivation (paper before Eq. 34).
        const double vnBefore =
            (pointVelocity(b0.vPrev, b0.omegaPrev, r0) - pointVelocity(b1.vPrev, b1.omegaPrev, r1)).dot(n);
        const double e = std::abs(vnBefore) <= 2.0 * gravity * h ? 0.0 : pair.restitution;
        const double change = std::max(-e * vnBefore, 0.0) - vn;  // Eq. 34
        if (std::abs(change) > kRestingSpeed)
            changePointVelocity(b0, b1, pointResponse(b0, r0, n), pointResponse(b1, r1, n), n, change);  // Eq. 33
        friction = true;
    }

    /// Eq. 29, Eq. 30, Eq. 33 with ERRATA item 2.
    [[gnu::flatten]] void dynamicFriction() {
        if (friction) applySinglePointFriction(pair, c, b0, b1, r0, r1, h);
    }
};

}  // namespace

double contactDepth(const Contact& contact, const Body& b0, const Body& b1) {
    const Vec3 p0 = b0.pointToWorld(contact.local0);
    const Vec3 p1 = b1.pointToWorld(contact.local1);
    return (p1 - p0).dot(contact.normal);
}

void solveContactPositions(ContactPair& pair, std::span<Contact> contacts, SolverContext& ctx) {
    const int points = static_cast<int>(std::min<size_t>(contacts.size(), kMaxPatchPoints));
    if (points == 1) return solveSinglePointPositions(pair, contacts[0], ctx);
    solvePatchPositions(pair, contacts.first(points), ctx);
}

void solveCollisionVelocities(const ContactPair& pair, const Contact& c, Body* bodies, double h) {
    Body& b0 = bodies[pair.body0];
    Body& b1 = bodies[pair.body1];
    const Vec3& n = c.normal;
    const Vec3 r0 = b0.q * c.local0;
    const Vec3 r1 = b1.q * c.local1;
    const PointResponse s0 = pointResponse(b0, r0, n);  // Eq. 2
    const PointResponse s1 = pointResponse(b1, r1, n);  // Eq. 3
    // An impulse p changes the normal velocity by p w (Eq. 33 the other way round).
    const double change = (c.restitutionImpulse - c.lambdaNormal / h) * (s0.w + s1.w);
    if (std::abs(change) > kRestingSpeed) changePointVelocity(b0, b1, s0, s1, n, change);
    applySinglePointFriction(pair, c, b0, b1, r0, r1, h);
}

void solveContactVelocities(const ContactPair& pair, std::span<const Contact> contacts,
                            Body* bodies, double h, double gravity) {
    Body& b0 = bodies[pair.body0];
    Body& b1 = bodies[pair.body1];
    const int points = static_cast<int>(std::min<size_t>(contacts.size(), kMaxPatchPoints));
    if (points == 1) {
        OnePointVelocities point(pair, contacts[0], bodies, h, gravity);
        point.normal();
        point.dynamicFriction();
        return;
    }
    solvePatchVelocities(pair, contacts.first(points), b0, b1, h, gravity);
}

}  // namespace substep
