// Fixed joint: the joint frames of both bodies coincide (paper 3.4.1 Eq. 18 and Eq. 19,
// 3.4.2).
//
//   Orientation: q = (q1 F1)(q0 F0)⁻¹ (Eq. 18, on the joint frames, with ERRATA item 1's
//   order) is the world rotation from body 0's joint frame to body 1's; body 0 turns by its
//   rotation vector (Eq. 19 with the exact angle rather than 2 q_xyz, which understates large
//   errors), always hard.
//   Position: the attachment Δx = p1 − p0 with the joint's compliance.
//   Both are solved together as one 6 x 6 block (applyWeldCorrection says why).

#include "physics/joints/joint_geometry.h"
#include "physics/joints/joint_rows.h"

namespace substep {

void solveFixedJoint(const Joint& joint, FixedJoint& fixed, SolverContext& ctx) {
    const JointAnchors anchors = jointAnchors(joint, ctx.bodies);
    const Quat difference =  // Eq. 18
        worldFrame1(joint, ctx.bodies) * worldFrame0(joint, ctx.bodies).conjugate();
    // The lever arms the block acts through: the current ones, or the substep's start
    // (JointProjection::Start; the gap and the rotation are measured on the current poses).
    const bool start = ctx.projection == JointProjection::Start;
    const Body& b0 = ctx.bodies[joint.body0];
    const Body& b1 = ctx.bodies[joint.body1];
    const Vec3 arm0 = start ? Vec3(directionOrientation(ctx, b0) * joint.anchor0) : anchors.r0;
    const Vec3 arm1 = start ? Vec3(directionOrientation(ctx, b1) * joint.anchor1) : anchors.r1;
    // Eq. 19 (rotationVector) and the attachment, as one block.
    applyWeldCorrection(ctx, joint.body0, joint.body1, anchors.p1 - anchors.p0, arm0, arm1,
                        rotationVector(difference), joint.compliance,
                        fixed.attachment.lambda, fixed.orientation.lambda, fixed.attachment.impulse,
                        fixed.orientation.impulse);
}

void appendFixedRows(const Joint& joint, FixedJoint& fixed, const SolverContext& ctx, JointRows& rows) {
    const JointAnchors anchors = jointAnchors(joint, ctx.bodies);
    const Vec3 rotation = rotationVector(  // Eq. 18, Eq. 19
        worldFrame1(joint, ctx.bodies) * worldFrame0(joint, ctx.bodies).conjugate());
    for (int k = 0; k < 3; ++k) rows.addRotation(joint, fixed.orientation, Vec3::Unit(k), rotation[k], 0.0);
    Vec3 arm0, arm1;
    attachmentArms(joint, ctx, arm0, arm1);
    rows.addPoint(joint, fixed.attachment, anchors.p1 - anchors.p0, arm0, arm1, joint.compliance);
}

JointEvaluation evaluateFixedJoint(const Joint& joint, const FixedJoint&, const Body* bodies) {
    const JointAnchors anchors = jointAnchors(joint, bodies);
    const double violation = (anchors.p1 - anchors.p0).norm();
    return {.error = violation, .elasticEnergy = elasticEnergy(violation, joint.compliance)};
}

}  // namespace substep
