#pragma once
/// Parts that joints are assembled from (as Jolt builds constraints from constraint parts):
/// the attachment, the orientation lock and the angle limit of Algorithm 3. Each reads the
/// bodies' current state, so every part sees the corrections made before it (non-linear
/// Gauss-Seidel, paper section 1).

#include "physics/correction.h"
#include "physics/joints/joint.h"

namespace substep {

/// World anchor points of a joint and their offsets from the centres of mass.
struct JointAnchors {
    Vec3 p0, p1;  ///< world points
    Vec3 r0, r1;  ///< offsets from the centres of mass
};

inline JointAnchors jointAnchors(const Joint& joint, const Body* bodies) {
    const Body& b0 = bodies[joint.body0];
    const Body& b1 = bodies[joint.body1];
    JointAnchors a;
    a.r0 = b0.toWorld(joint.anchor0);
    a.r1 = b1.toWorld(joint.anchor1);
    a.p0 = b0.x + a.r0;
    a.p1 = b1.x + a.r1;
    return a;
}

/// The joint frames in world space: columns are the axes a, b, c.
inline Quat worldFrame0(const Joint& joint, const Body* bodies) {
    return bodies[joint.body0].q * joint.frame0;
}
inline Quat worldFrame1(const Joint& joint, const Body* bodies) {
    return bodies[joint.body1].q * joint.frame1;
}

/// Positional part, 3.4.2: moves body 0's anchor by `delta` relative to body 1's anchor.
inline void solvePositionPart(Joint& joint, SolverContext& ctx, const JointAnchors& anchors,
                              const Vec3& delta, double compliance, double& lambda) {
    joint.linearImpulse += applyPositionalCorrection(ctx, joint.body0, joint.body1, delta,
                                                     anchors.r0, anchors.r1, compliance, lambda);
}

/// Attachment, 3.4.2: Δx = Δr = p1 − p0 (a zero-rest-length spring when compliant), projected
/// with the full 3 x 3 inverse mass (applyPointCorrection explains why).
inline void solveAttachment(Joint& joint, SolverContext& ctx) {
    joint.linearImpulse +=
        applyAttachmentCorrection(ctx, joint.body0, joint.body1, joint.anchor0, joint.anchor1,
                                  joint.compliance, joint.lambdaPoint);
}

/// Angular part, 3.3.2: turns body 0 by `rotation` relative to body 1.
inline void solveRotationPart(Joint& joint, SolverContext& ctx, const Vec3& rotation,
                              double compliance, double& lambda) {
    joint.angularImpulse += applyAngularCorrection(ctx, joint.body0, joint.body1, rotation,
                                                   compliance, lambda);
}

/// Hard orientation lock (Eqs. 18-19, with the exact rotation vector): turns body 0's joint
/// frame onto body 1's, in block form (applyRotationCorrection says why).
inline void solveOrientationLock(Joint& joint, SolverContext& ctx) {
    const Quat difference = worldFrame1(joint, ctx.bodies) * worldFrame0(joint, ctx.bodies).conjugate();
    joint.angularImpulse += applyRotationCorrection(ctx, joint.body0, joint.body1,
                                                    rotationVector(difference), 0.0,
                                                    joint.lambdaRotation);
}

/// Algorithm 3 (with ERRATA items 3-4): keeps the angle from n0 to n1 about n inside
/// [lower, upper]. n, n0, n1 are unit vectors, n0 and n1 perpendicular to n.
inline void solveAngleLimit(Joint& joint, SolverContext& ctx, const Vec3& n, const Vec3& n0,
                            const Vec3& n1, double lower, double upper, double compliance,
                            double& lambda) {
    const double phi = signedAngle(n, n0, n1);
    if (phi >= lower && phi <= upper) return;
    const double clamped = phi < lower ? lower : upper;
    // n0 and n1 lie in the plane normal to n, so the turn from the limit's direction to n1 is
    // about n by the excess, taken the short way round: no need to build that direction.
    double excess = phi - clamped;
    if (excess > M_PI) excess -= 2.0 * M_PI;
    if (excess <= -M_PI) excess += 2.0 * M_PI;
    solveRotationPart(joint, ctx, excess * n, compliance, lambda);
}

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

/// Per-type solve and evaluation functions (one file each).
struct JointEvaluation {
    double error = 0.0;          ///< positional violation (m)
    double elasticEnergy = 0.0;  ///< J
};

void solveDistanceJoint(Joint& joint, SolverContext& ctx);
void solveFixedJoint(Joint& joint, SolverContext& ctx);
void solveHingeJoint(Joint& joint, SolverContext& ctx);
void solveSphericalJoint(Joint& joint, SolverContext& ctx);
void solvePrismaticJoint(Joint& joint, SolverContext& ctx);

JointEvaluation evaluateDistanceJoint(const Joint& joint, const Body* bodies);
JointEvaluation evaluateFixedJoint(const Joint& joint, const Body* bodies);
JointEvaluation evaluateHingeJoint(const Joint& joint, const Body* bodies);
JointEvaluation evaluateSphericalJoint(const Joint& joint, const Body* bodies);
JointEvaluation evaluatePrismaticJoint(const Joint& joint, const Body* bodies);

/// The hinge angle (rad, right-hand rule about body 0's axis) of body 1 relative to body 0.
double hingeAngle(const Joint& joint, const Body* bodies);

}  // namespace substep
