// Tests engine/physics/correction.cpp and correction_kernels.h: the two correction operations of
// paper 3.3 (Eqs. 2-16), their vector forms (the point attachment and the weld), and the velocity
// correction of Eq. 33, against their closed forms and invariants on hand-made bodies.

#include "physics/correction.h"
#include "physics/correction_kernels.h"

#include "physics_test_support.h"

#include <gtest/gtest.h>

#include <array>
#include <vector>
#include <cmath>

namespace substep {
namespace {

/// Two free bodies: index 0 a sphere of mass m0, index 1 a box of mass m1.
struct Pair {
    std::array<Body, 2> bodies;
    std::array<JacobiDelta, 2> deltas;
    SolverContext ctx;

    Pair(double m0, double m1, double h, SolverType solver = SolverType::GaussSeidel) {
        bodies[0] = makeBody({.shape = sphereShape(0.2), .mass = m0, .position = Vec3(0, 0, 0)});
        bodies[1] = makeBody(
            {.shape = boxShape(Vec3(0.2, 0.4, 0.6)), .mass = m1, .position = Vec3(1, 0, 0)});
        ctx = SolverContext{.bodies = bodies.data(),
                            .h = h,
                            .invH2 = 1.0 / (h * h),
                            .solver = solver,
                            .deltas = deltas.data()};
    }
};

// Eqs. 2-7 at the centres of mass: w = 1/m, Δλ = c/(w0 + w1), body 0 moves c w0/(w0 + w1)
// along the correction and body 1 the rest the other way; the centre of mass stays.
TEST(PositionalCorrectionTest, SharesByInverseMassAndKeepsCentreOfMass) {
    const double m0 = 1.0, m1 = 3.0;
    Pair pair(m0, m1, 0.01);
    const Vec3 com = (m0 * pair.bodies[0].x + m1 * pair.bodies[1].x) / (m0 + m1);
    const Quat q0 = pair.bodies[0].q, q1 = pair.bodies[1].q;
    const Vec3 delta(0.1, -0.05, 0.02);
    double lambda = 0.0;
    const Vec3 p =
        applyPositionalCorrection(pair.ctx, 0, 1, delta, Vec3::Zero(), Vec3::Zero(), 0.0, lambda);
    const double w0 = 1.0 / m0, w1 = 1.0 / m1;
    EXPECT_NEAR(lambda, delta.norm() / (w0 + w1), 1e-15);
    EXPECT_LT((p - delta / (w0 + w1)).norm(), 1e-15);
    EXPECT_LT((pair.bodies[0].x - delta * (w0 / (w0 + w1))).norm(), 1e-15);
    EXPECT_LT((pair.bodies[1].x - (Vec3(1, 0, 0) - delta * (w1 / (w0 + w1)))).norm(), 1e-15);
    // The relative offset closes completely with zero compliance.
    EXPECT_LT(((pair.bodies[1].x - pair.bodies[0].x) - (Vec3(1, 0, 0) - delta)).norm(), 1e-15);
    const Vec3 comAfter = (m0 * pair.bodies[0].x + m1 * pair.bodies[1].x) / (m0 + m1);
    EXPECT_LT((comAfter - com).norm(), 1e-15);
    // Centred corrections do not turn the bodies.
    EXPECT_TRUE(pair.bodies[0].q.coeffs() == q0.coeffs());
    EXPECT_TRUE(pair.bodies[1].q.coeffs() == q1.coeffs());
}

// Eq. 4 with compliance: Δλ = (c − α̃λ)/(w0 + w1 + α̃), α̃ = α/h², and λ accumulates (Eq. 5).
TEST(PositionalCorrectionTest, CompliantMultiplierFollowsEq4) {
    const double m0 = 2.0, m1 = 0.5, h = 1.0 / 600.0, alpha = 1e-4;
    Pair pair(m0, m1, h);
    const double w = 1.0 / m0 + 1.0 / m1, alphaTilde = alpha / (h * h);
    const Vec3 delta(0.0, 0.03, 0.0);
    double lambda = 0.0;
    applyPositionalCorrection(pair.ctx, 0, 1, delta, Vec3::Zero(), Vec3::Zero(), alpha, lambda);
    const double first = 0.03 / (w + alphaTilde);
    EXPECT_NEAR(lambda, first, 1e-15);
    applyPositionalCorrection(pair.ctx, 0, 1, delta, Vec3::Zero(), Vec3::Zero(), alpha, lambda);
    EXPECT_NEAR(lambda, first + (0.03 - alphaTilde * first) / (w + alphaTilde), 1e-15);
}

// Eqs. 2 and 8 off the centre: w0 = 1/m0 + (r × n)ᵀ I⁻¹ (r × n), the body turns by
// I⁻¹ (r × p), and to first order the anchor point moves c w0/(w0 + w1) along n.
TEST(PositionalCorrectionTest, OffCentreCorrectionTurnsTheBody) {
    const double h = 0.01;
    Pair pair(1.0, 1.0, h);
    Body& box = pair.bodies[1];
    box.invMass = 0.0;  // a static partner takes no share
    box.invInertia.setZero();
    Body& sphere = pair.bodies[0];
    const double inertia = 0.4 * 1.0 * 0.2 * 0.2;  // solid sphere 2/5 m r²
    ASSERT_NEAR(sphere.inertia.x(), inertia, 1e-15);

    const Vec3 r(0.0, 0.2, 0.0), n(1.0, 0.0, 0.0);
    const Quat start = sphere.q;
    const double c = 1e-6;  // small: the linearised rotation is exact to first order
    double lambda = 0.0;
    applyPositionalCorrection(pair.ctx, 0, 1, c * n, r, Vec3::Zero(), 0.0, lambda);
    const double w0 = 1.0 + r.cross(n).squaredNorm() / inertia;  // Eq. 2: 1 + 0.04/0.016 = 3.5
    EXPECT_NEAR(lambda, c / w0, 1e-15);
    // Linear part: the centre moves p/m.
    EXPECT_NEAR(sphere.x.x(), c / w0, 1e-15);
    // Angular part: turns about r × n = −z by |r| Δλ / I.
    const Vec3 turned = test::turnBetween(start, sphere.q);
    EXPECT_NEAR(turned.z(), -0.2 * (c / w0) / inertia, 1e-15);
    // The anchor point moves the full correction (the static partner takes none).
    const Vec3 anchor = sphere.x + (sphere.q * start.conjugate()) * r;
    EXPECT_NEAR(anchor.x(), c, 1e-12);
}

// --- Point attachment (vector form of Eqs. 2-9) -------------------------------------------------

/// World inertia tensor of a body from its principal moments.
Mat3 inertiaOf(const Body& b) {
    const Mat3 r = b.q.toRotationMatrix();
    return r * b.inertia.asDiagonal() * r.transpose();
}

/// The two bodies of `pair`, moved off their centres and turned, anchored at a common point.
struct Anchored {
    Pair pair;
    Vec3 point{0.4, 0.3, -0.2};  ///< the common anchor (world)
    Vec3 r0, r1;                 ///< offsets from the centres of mass
    Body before0, before1;

    explicit Anchored(double m0 = 1.0, double m1 = 3.0, double h = 0.01) : pair(m0, m1, h) {
        const Quat turn(Eigen::AngleAxisd(0.8, Vec3(1, -2, 0.5).normalized()));
        pair.bodies[1].q = (turn * pair.bodies[1].q).normalized();
        r0 = point - pair.bodies[0].x;
        r1 = point - pair.bodies[1].x;
        before0 = pair.bodies[0];
        before1 = pair.bodies[1];
    }
    /// How far body 0's anchor moved relative to body 1's (first order in the turns).
    Vec3 relativeAnchorMotion() const {
        const Body& b0 = pair.bodies[0];
        const Body& b1 = pair.bodies[1];
        const Vec3 p0 = b0.x + (b0.q * before0.q.conjugate()) * r0;
        const Vec3 p1 = b1.x + (b1.q * before1.q.conjugate()) * r1;
        return (p0 - point) - (p1 - point);
    }
    /// Σ I Δθ + x × m Δx over both bodies: the angular impulse about the origin, 0 when the
    /// correction's impulses act at one point.
    Vec3 angularImpulse() const {
        Vec3 sum = Vec3::Zero();
        for (int i = 0; i < 2; ++i) {
            const Body& b = pair.bodies[i];
            const Body& a = i == 0 ? before0 : before1;
            sum += inertiaOf(a) * test::turnBetween(a.q, b.q) + a.x.cross(b.mass * (b.x - a.x));
        }
        return sum;
    }
};

// A hard point correction makes body 0's anchor move by exactly delta relative to body 1's, in
// every direction (to first order in the small turns), whatever the bodies' shapes and offsets;
// it keeps linear momentum and, the impulses acting at one point, angular momentum.
TEST(PointCorrectionTest, ClosesTheGapInEveryDirection) {
    for (const Vec3& direction : {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(1, -2, 3)}) {
        Anchored rig;
        const Vec3 delta = 1e-6 * direction.normalized();
        Vec3 lambda = Vec3::Zero();
        const Vec3 p = applyPointCorrection(rig.pair.ctx, 0, 1, delta, rig.r0, rig.r1, 0.0, lambda);
        EXPECT_LT((rig.relativeAnchorMotion() - delta).norm(), 1e-6 * delta.norm());
        EXPECT_LT((lambda - p).norm(), 1e-20);
        const Body& b0 = rig.pair.bodies[0];
        const Body& b1 = rig.pair.bodies[1];
        EXPECT_LT((b0.mass * (b0.x - rig.before0.x) + b1.mass * (b1.x - rig.before1.x)).norm(),
                  1e-14);  // rounding of positions near 1 m
        EXPECT_LT(rig.angularImpulse().norm(), 1e-6 * delta.norm());
    }
}

// With the anchors at the centres there is no turning: Δλ = Δr/(w0 + w1 + α̃) as a vector
// (Eq. 4 per direction), and λ accumulates.
TEST(PointCorrectionTest, CompliantMultiplierAtTheCentres) {
    const double m0 = 2.0, m1 = 0.5, h = 1.0 / 600.0, alpha = 1e-4;
    Pair pair(m0, m1, h);
    const double w = 1.0 / m0 + 1.0 / m1, alphaTilde = alpha / (h * h);
    const Vec3 delta(0.01, -0.02, 0.03);
    Vec3 lambda = Vec3::Zero();
    applyPointCorrection(pair.ctx, 0, 1, delta, Vec3::Zero(), Vec3::Zero(), alpha, lambda);
    const Vec3 first = delta / (w + alphaTilde);
    EXPECT_LT((lambda - first).norm(), 1e-15);
    applyPointCorrection(pair.ctx, 0, 1, delta, Vec3::Zero(), Vec3::Zero(), alpha, lambda);
    EXPECT_LT((lambda - (first + (delta - alphaTilde * first) / (w + alphaTilde))).norm(), 1e-15);
}

// Against a static body, a sphere (isotropic I) anchored at r takes the impulse
// p = K⁻¹ Δ with K = 1/m + (|r|² 1 − r rᵀ)/I.
TEST(PointCorrectionTest, MatchesTheClosedFormInverseMass) {
    Pair pair(1.5, 1.0, 0.01);
    pair.bodies[1].invMass = 0.0;
    pair.bodies[1].invInertia.setZero();
    const double inertia = 0.4 * 1.5 * 0.2 * 0.2;
    const Vec3 r(0.1, 0.2, -0.05), delta(1e-3, 2e-3, -1e-3);
    const Mat3 k =
        Mat3::Identity() / 1.5 + (r.squaredNorm() * Mat3::Identity() - r * r.transpose()) / inertia;
    Vec3 lambda = Vec3::Zero();
    const Vec3 p = applyPointCorrection(pair.ctx, 0, 1, delta, r, Vec3::Zero(), 0.0, lambda);
    EXPECT_LT((p - k.inverse() * delta).norm(), 1e-12 * p.norm());
}

// --- Weld (attachment and orientation lock together) -------------------------------------------

// A hard weld correction moves body 0's anchor by delta and turns body 0 by `rotation`, both
// relative to body 1, in one projection (to first order), keeping linear and angular momentum.
TEST(WeldCorrectionTest, ClosesGapAndTurnTogether) {
    Anchored rig;
    const Vec3 delta(1e-6, -2e-6, 0.5e-6), rotation(-1e-6, 0.5e-6, 2e-6);
    Vec3 lambdaPoint = Vec3::Zero(), lambdaAngle = Vec3::Zero(), impulse = Vec3::Zero(),
         angularImpulse = Vec3::Zero();
    applyWeldCorrection(rig.pair.ctx, 0, 1, delta, rig.r0, rig.r1, rotation, 0.0, lambdaPoint,
                        lambdaAngle, impulse, angularImpulse);
    const Body& b0 = rig.pair.bodies[0];
    const Body& b1 = rig.pair.bodies[1];
    const Vec3 relativeTurn =
        test::turnBetween(rig.before0.q, b0.q) - test::turnBetween(rig.before1.q, b1.q);
    EXPECT_LT((rig.relativeAnchorMotion() - delta).norm(), 1e-5 * delta.norm());
    EXPECT_LT((relativeTurn - rotation).norm(), 1e-5 * rotation.norm());
    EXPECT_LT((b0.mass * (b0.x - rig.before0.x) + b1.mass * (b1.x - rig.before1.x)).norm(),
              1e-14);  // rounding of positions near 1 m
    EXPECT_LT(rig.angularImpulse().norm(), 1e-5 * (impulse.norm() + angularImpulse.norm()));
    EXPECT_LT((impulse - lambdaPoint).norm(), 1e-20);
}

// Eqs. 11-16: a rotation θ about a principal axis is shared by inverse inertia.
TEST(AngularCorrectionTest, SharesByInverseInertia) {
    Pair pair(1.0, 4.0, 0.01);
    const double i0 = pair.bodies[0].inertia.x();            // sphere: isotropic
    const double i1 = 4.0 * (0.2 * 0.2 + 0.4 * 0.4) / 12.0;  // box about z: m (a² + b²)/12
    const Vec3 rotation(0.0, 0.0, 1e-4);
    const Quat start0 = pair.bodies[0].q, start1 = pair.bodies[1].q;
    double lambda = 0.0;
    const Vec3 p = applyAngularCorrection(pair.ctx, 0, 1, rotation, 0.0, lambda);
    const double w0 = 1.0 / i0, w1 = 1.0 / i1;
    EXPECT_NEAR(lambda, 1e-4 / (w0 + w1), 1e-15);
    EXPECT_NEAR(p.z(), lambda, 1e-18);
    const Vec3 turn0 = test::turnBetween(start0, pair.bodies[0].q);
    const Vec3 turn1 = test::turnBetween(start1, pair.bodies[1].q);
    EXPECT_NEAR(turn0.z(), 1e-4 * w0 / (w0 + w1), 1e-12);
    EXPECT_NEAR(turn1.z(), -1e-4 * w1 / (w0 + w1), 1e-12);
    // Positions are untouched.
    EXPECT_EQ(pair.bodies[0].x, Vec3::Zero());
    EXPECT_EQ(pair.bodies[1].x, Vec3(1, 0, 0));
    // Angular momentum: I0 Δθ0 + I1 Δθ1 = 0.
    EXPECT_NEAR(i0 * turn0.z() + i1 * turn1.z(), 0.0, 1e-15);
}

// A correction turns a body by exactly the angle it computes (Eq. 15 by the exponential map),
// below and above the turn's series range (0.2 rad) and about any axis: a sphere corrected
// against the static world (index 0 of a world-like pair, w = 0) turns by the whole rotation,
// which Eigen's angle-axis gives independently, and its quaternion stays unit.
TEST(AngularCorrectionTest, TurnsByTheExactAngle) {
    for (const double angle : {1e-7, 1e-3, 0.05, 0.19, 0.21, 0.8}) {
        std::array<Body, 2> bodies;
        bodies[1] = makeBody({.shape = sphereShape(0.3), .mass = 2.0,
                              .orientation = Quat(Eigen::AngleAxisd(1.3, Vec3(1, -1, 2).normalized()))});
        SolverContext ctx{.bodies = bodies.data(), .h = 0.01, .invH2 = 1e4};
        const Vec3 axis = Vec3(0.3, -0.5, 0.8).normalized();
        const Quat start = bodies[1].q;
        double lambda = 0.0;
        // Body 0 (the world) turns by `rotation` relative to body 1: body 1 turns by its opposite.
        applyAngularCorrection(ctx, 0, 1, -angle * axis, 0.0, lambda);
        const Quat expected = Quat(Eigen::AngleAxisd(angle, axis)) * start;
        EXPECT_LT((bodies[1].q.coeffs() - expected.coeffs()).norm(), 4e-16) << "angle " << angle;
        EXPECT_NEAR(bodies[1].q.norm(), 1.0, 4e-16) << "angle " << angle;
    }
}

// Zero-length (and NaN-free tiny) corrections do nothing and leave λ alone.
TEST(CorrectionDegenerateTest, ZeroLengthCorrectionsAreNoOps) {
    Pair pair(1.0, 1.0, 0.01);
    const Body before0 = pair.bodies[0], before1 = pair.bodies[1];
    double lambda = 0.25;
    for (const Vec3& zero : {Vec3(Vec3::Zero()), Vec3(1e-300, 0.0, 0.0), Vec3(0.0, -0.0, 0.0)}) {
        EXPECT_EQ(applyPositionalCorrection(pair.ctx, 0, 1, zero, Vec3(0, 0.1, 0), Vec3::Zero(),
                                            0.01, lambda),
                  Vec3::Zero());
        EXPECT_EQ(applyAngularCorrection(pair.ctx, 0, 1, zero, 0.0, lambda), Vec3::Zero());
    }
    EXPECT_EQ(lambda, 0.25);
    EXPECT_EQ(pair.bodies[0].x, before0.x);
    EXPECT_EQ(pair.bodies[1].x, before1.x);
    EXPECT_TRUE(pair.bodies[0].q.coeffs() == before0.q.coeffs());
    // Two static bodies: no mass to move, no NaN.
    pair.bodies[0].invMass = pair.bodies[1].invMass = 0.0;
    pair.bodies[0].invInertia.setZero();
    pair.bodies[1].invInertia.setZero();
    EXPECT_EQ(applyPositionalCorrection(pair.ctx, 0, 1, Vec3(1, 0, 0), Vec3::Zero(), Vec3::Zero(),
                                        0.0, lambda),
              Vec3::Zero());
    EXPECT_EQ(applyAngularCorrection(pair.ctx, 0, 1, Vec3(0, 1, 0), 0.0, lambda), Vec3::Zero());
    EXPECT_TRUE(pair.bodies[0].x.allFinite() && pair.bodies[0].q.coeffs().allFinite());
    EXPECT_EQ(lambda, 0.25);
}

// Jacobi: corrections are gathered, not applied, until applyJacobiDeltas; a body corrected
// twice in one iteration moves by the sum of both corrections.
TEST(CorrectionJacobiTest, GathersThenAppliesTheSum) {
    Pair pair(1.0, 1.0, 0.01, SolverType::Jacobi);
    pair.bodies[1].invMass = 0.0;  // static partner
    pair.bodies[1].invInertia.setZero();
    double l1 = 0.0, l2 = 0.0;
    applyPositionalCorrection(pair.ctx, 0, 1, Vec3(0.2, 0, 0), Vec3::Zero(), Vec3::Zero(), 0.0, l1);
    applyPositionalCorrection(pair.ctx, 0, 1, Vec3(0, 0.4, 0), Vec3::Zero(), Vec3::Zero(), 0.0, l2);
    EXPECT_EQ(pair.bodies[0].x, Vec3::Zero());  // nothing moved yet
    EXPECT_EQ(pair.deltas[0].count, 2u);
    applyJacobiDeltas(pair.bodies.data(), pair.deltas.data(), 2);
    EXPECT_LT((pair.bodies[0].x - Vec3(0.2, 0.4, 0)).norm(), 1e-15);
    EXPECT_EQ(pair.deltas[0].count, 0u);  // cleared for the next iteration
    EXPECT_EQ(pair.bodies[1].x, Vec3(1, 0, 0));
}

// Eq. 33: the relative velocity of the two points changes by exactly Δv, momentum is kept.
TEST(VelocityCorrectionTest, ChangesRelativeVelocityByDelta) {
    Pair pair(1.0, 3.0, 0.01);
    Body& b0 = pair.bodies[0];
    Body& b1 = pair.bodies[1];
    b0.v = Vec3(1, 0, 0);
    b1.v = Vec3(-1, 0.5, 0);
    const Vec3 momentum = 1.0 * b0.v + 3.0 * b1.v;
    const Vec3 dv(-0.6, 0.3, 0.1);
    const Vec3 relative = b0.v - b1.v;
    applyVelocityCorrection(b0, b1, dv, Vec3::Zero(), Vec3::Zero());
    EXPECT_LT(((b0.v - b1.v) - (relative + dv)).norm(), 1e-14);
    EXPECT_LT((1.0 * b0.v + 3.0 * b1.v - momentum).norm(), 1e-14);

    // Off-centre on body 0 against a static body 1: the point velocity v + ω × r changes by Δv
    // along Δv's direction.
    b1.invMass = 0.0;
    b1.invInertia.setZero();
    b1.v.setZero();
    b0.v.setZero();
    b0.omega.setZero();
    const Vec3 r(0.0, 0.2, 0.0), n(0.7, 0.0, 0.0);
    applyVelocityCorrection(b0, b1, n, r, Vec3::Zero());
    EXPECT_NEAR((b0.v + b0.omega.cross(r)).x(), 0.7, 1e-14);
    EXPECT_GT(b0.omega.norm(), 0.0);
}

// --- Block rotation correction (vector form of Eqs. 11-16) ---------------------------------------

/// Two boxes of uneven inertia, turned away from the world axes and from each other.
Pair unevenPair() {
    Pair pair(2.0, 3.0, 0.01);
    pair.bodies[0] = makeBody({.shape = boxShape(Vec3(0.1, 0.5, 0.9)), .mass = 2.0});
    pair.bodies[0].q = Quat(Eigen::AngleAxisd(0.7, Vec3(1, 2, -1).normalized()));
    pair.bodies[1].q = Quat(Eigen::AngleAxisd(-1.1, Vec3(0.3, -1, 2).normalized())) * pair.bodies[1].q;
    return pair;
}

// A hard alignment with a free axis f (a hinge's, Eq. 20 in block form) turns body 0 relative to
// body 1 by the rotation's part normal to f, gives no angular impulse about f, and shares the
// turn by inverse inertia: I0 Δθ0 = Δλ = −I1 Δθ1 (world inertia tensors; angular momentum
// kept). Checked on bodies whose principal axes lie along none of the directions involved, for
// free axes near x and away from it (either helper of the plane's basis), of any length (the
// hinge passes a0 + a1 unnormalised: the result does not depend on it).
TEST(RotationCorrectionTest, FreeAxisAlignmentTurnsInThePlaneNormalToTheAxis) {
    for (const Vec3& direction : {Vec3(0.2, 1.0, -0.4), Vec3(1.0, 0.1, -0.3)})
        for (const double length : {1.0, 0.3, 2.0, 1e3}) {
            SCOPED_TRACE(::testing::Message() << "axis " << direction.transpose() << " length " << length);
            Pair pair = unevenPair();
            const Body before0 = pair.bodies[0], before1 = pair.bodies[1];
            const Vec3 free = direction.normalized();
            const Vec3 freeAxis = length * free;
            const Vec3 rotation = 1e-5 * Vec3(0.3, -0.1, 0.8) + 2e-5 * free;  // a part along f too
            Vec3 lambda = Vec3::Zero();
            const Vec3 impulse = applyRotationCorrection(pair.ctx, 0, 1, rotation, 0.0, lambda, &freeAxis);
            EXPECT_NEAR(impulse.dot(free), 0.0, 1e-12 * impulse.norm());
            EXPECT_EQ(impulse, lambda);
            const Vec3 turn0 = test::turnBetween(before0.q, pair.bodies[0].q);
            const Vec3 turn1 = test::turnBetween(before1.q, pair.bodies[1].q);
            const Vec3 relative = turn0 - turn1;
            const Vec3 inPlane = rotation - rotation.dot(free) * free;
            EXPECT_LT((relative - relative.dot(free) * free - inPlane).norm(), 1e-9 * inPlane.norm());
            EXPECT_LT((inertiaOf(before0) * turn0 - impulse).norm(), 1e-9 * impulse.norm());
            EXPECT_LT((inertiaOf(before1) * turn1 + impulse).norm(), 1e-9 * impulse.norm());
        }
}

// Without a free axis the lock turns body 0 relative to body 1 by the whole rotation, shared by
// inverse inertia: Δλ = (I0⁻¹ + I1⁻¹)⁻¹ θ.
TEST(RotationCorrectionTest, OrientationLockSharesTheTurnByInverseInertia) {
    Pair pair = unevenPair();
    const Body before0 = pair.bodies[0], before1 = pair.bodies[1];
    const Vec3 rotation = 1e-5 * Vec3(0.3, -0.9, 0.5);
    Vec3 lambda = Vec3::Zero();
    const Vec3 impulse = applyRotationCorrection(pair.ctx, 0, 1, rotation, 0.0, lambda);
    const Mat3 k = inertiaOf(before0).inverse() + inertiaOf(before1).inverse();
    EXPECT_LT((impulse - k.inverse() * rotation).norm(), 1e-12 * impulse.norm());
    const Vec3 turn0 = test::turnBetween(before0.q, pair.bodies[0].q);
    const Vec3 turn1 = test::turnBetween(before1.q, pair.bodies[1].q);
    EXPECT_LT((turn0 - turn1 - rotation).norm(), 1e-9 * rotation.norm());
}


// --- Angular forms without normalising (correction_kernels.h, applyAngularVelocityCorrection) ---

/// World inverse inertia R diag(I⁻¹) Rᵀ of a turning body, built here from its principal moments.
Mat3 worldInverseInertiaOf(const Body& body) {
    const Mat3 r = body.q.toRotationMatrix();
    return r * body.inertia.cwiseInverse().asDiagonal() * r.transpose();
}

/// Body pairs of every kind of inertia: a capsule (two equal moments) and a box (three
/// different), a sphere (three equal) and a rod of square section, turned off the world axes.
std::vector<std::array<Body, 2>> inertiaPairs() {
    const Quat tilt0(Eigen::AngleAxisd(0.7, Vec3(1, 2, -1).normalized()));
    const Quat tilt1(Eigen::AngleAxisd(-1.1, Vec3(0.3, -1, 2).normalized()));
    std::vector<std::array<Body, 2>> pairs;
    pairs.push_back({makeBody({.shape = capsuleShape(0.04, 0.04), .mass = 0.47, .orientation = tilt0}),
                     makeBody({.shape = boxShape(Vec3(0.1, 0.5, 0.9)), .mass = 3.0, .orientation = tilt1})});
    pairs.push_back({makeBody({.shape = sphereShape(0.2), .mass = 1.0, .orientation = tilt1}),
                     makeBody({.shape = boxShape(Vec3(1.0, 0.1, 0.1)), .mass = 20.0, .orientation = tilt0})});
    return pairs;
}

// The joint damping's velocity form of Eqs. 11-16 (Eq. 33 on ω, Eq. 32's Δω): an angular impulse
// p = Δω / w along n = Δω/|Δω|, w = nᵀ (I0⁻¹ + I1⁻¹) n (Eq. 11, Eq. 12), so ω0 − ω1 changes by
// |Δω| along n (across n too where the inertias are uneven: the scalar form), each ω by ± I⁻¹ p,
// and the angular momentum I0 ω0 + I1 ω1 is kept; for bodies of every kind of inertia, Δω of any
// direction and of sizes 1e-9 to 1e3 (w is taken on Δω unnormalised: a wrong |Δω|² factor would
// miss by that factor). Against a static body, ω0 alone takes the change along n.
TEST(AngularVelocityCorrectionTest, ChangesRelativeSpinByDeltaAndKeepsAngularMomentum) {
    for (std::array<Body, 2> pair : inertiaPairs()) {
        for (const double size : {1e-9, 1e-3, 1.0, 1e3}) {
            for (const Vec3& direction : {Vec3(1, 0, 0), Vec3(0.3, -0.5, 0.8), Vec3(-2, 1, 0.5)}) {
                Body& b0 = pair[0];
                Body& b1 = pair[1];
                b0.omega = Vec3(0.4, -1.0, 2.0);
                b1.omega = Vec3(-3.0, 0.2, 0.7);
                const Vec3 delta = size * direction.normalized();
                const Vec3 relative = b0.omega - b1.omega;
                const Vec3 momentum = worldInverseInertiaOf(b0).inverse() * b0.omega +
                                      worldInverseInertiaOf(b1).inverse() * b1.omega;
                const Vec3 n = delta / size;
                const double w = n.dot((worldInverseInertiaOf(b0) + worldInverseInertiaOf(b1)) * n);
                const Vec3 p = applyAngularVelocityCorrection(b0, b1, delta);
                EXPECT_LT((p - delta / w).norm(), 1e-12 * size / w) << size;
                // ω of order 1 is read back to 1e-14: the resolution of the smallest Δω.
                const double tolerance = 1e-12 * size + 1e-14;
                EXPECT_NEAR(n.dot((b0.omega - b1.omega) - relative), size, tolerance) << size;
                const Vec3 momentumAfter = worldInverseInertiaOf(b0).inverse() * b0.omega +
                                           worldInverseInertiaOf(b1).inverse() * b1.omega;
                EXPECT_LT((momentumAfter - momentum).norm(), 1e-12 * momentum.norm()) << size;
                // p is the angular impulse given to body 0: ω0 changes by I0⁻¹ p.
                EXPECT_LT((worldInverseInertiaOf(b0) * p - (b0.omega - Vec3(0.4, -1.0, 2.0))).norm(), tolerance) << size;
            }
        }
        Body fixed;  // static: w = 0
        pair[0].omega = Vec3(0.4, -1.0, 2.0);
        const Vec3 delta(0.2, 0.1, -0.3);
        applyAngularVelocityCorrection(pair[0], fixed, delta);
        EXPECT_NEAR(delta.normalized().dot(pair[0].omega - Vec3(0.4, -1.0, 2.0)), delta.norm(), 1e-14);
        EXPECT_EQ(fixed.omega, Vec3::Zero());
    }
}

// An angle limit's correction about a unit axis n by θ (axisCorrection: no rotation vector to
// normalise) is Eqs. 11-16 along n: Δλ = θ / (w0 + w1) with w = nᵀ I⁻¹ n (Eq. 11, Eq. 12), each
// body turned by ± I⁻¹ n Δλ, so the turn of body 0 relative to body 1 about n is θ, and the
// angular momentum I0 Δθ0 + I1 Δθ1 is zero. For both kinds of pairs, axes off every principal
// axis, and angles from 1e-8 to 0.3 rad (beyond the turn's series range).
TEST(AngularCorrectionTest, AboutAUnitAxisSharesByInverseInertiaAlongIt) {
    for (const std::array<Body, 2>& start : inertiaPairs()) {
        for (const double theta : {1e-8, 1e-4, 0.05, 0.3}) {
            for (const Vec3& direction : {Vec3(0, 0, 1), Vec3(0.3, -0.5, 0.8), Vec3(-2, 1, 0.5)}) {
                std::array<Body, 2> bodies = start;
                SolverContext ctx{.bodies = bodies.data(), .h = 0.01, .invH2 = 1e4};
                const Vec3 n = direction.normalized();
                const Mat3 inverse0 = worldInverseInertiaOf(bodies[0]);
                const Mat3 inverse1 = worldInverseInertiaOf(bodies[1]);
                const double w0 = n.dot(inverse0 * n), w1 = n.dot(inverse1 * n);
                double lambda = 0.0;
                const Vec3 p = correction_kernels::axisCorrection(ctx, 0, 1, bodies[0].q.toRotationMatrix(),
                                                                  bodies[1].q.toRotationMatrix(), n, theta, 0.0, lambda);
                EXPECT_NEAR(lambda, theta / (w0 + w1), 1e-14 * lambda) << theta;
                EXPECT_LT((p - lambda * n).norm(), 1e-15 * lambda);
                // The turns are read back from unit quaternions: 1e-15 rad is their resolution.
                const Vec3 turn0 = test::turnBetween(start[0].q, bodies[0].q);
                const Vec3 turn1 = test::turnBetween(start[1].q, bodies[1].q);
                const double tolerance = 1e-9 * theta + 1e-15;
                EXPECT_LT((turn0 - inverse0 * n * lambda).norm(), tolerance) << theta;
                EXPECT_LT((turn1 + inverse1 * n * lambda).norm(), tolerance) << theta;
                EXPECT_NEAR(n.dot(turn0 - turn1), theta, tolerance) << theta;
                const Mat3 inertia0 = inverse0.inverse(), inertia1 = inverse1.inverse();
                EXPECT_LT((inertia0 * turn0 + inertia1 * turn1).norm(), tolerance * (inertia0.norm() + inertia1.norm()))
                    << theta;
            }
        }
    }
}

}  // namespace
}  // namespace substep
