// Fixed joint: the joint frames of both bodies coincide (paper 3.4.1 Eqs. 18-19, 3.4.2).
//
//   Orientation: q = (q1 F1)(q0 F0)⁻¹ is the world rotation from body 0's joint frame to
//   body 1's; body 0 turns by its rotation vector (exact angle rather than 2 q_xyz, which
//   understates large errors), always hard.
//   Position: the attachment Δx = p1 − p0 with the joint's compliance.
//   Both are solved together as one 6 x 6 block (applyWeldCorrection says why).

#include "physics/joints/joint_parts.h"

namespace substep {

void solveFixedJoint(Joint& joint, SolverContext& ctx) {
    const JointAnchors anchors = jointAnchors(joint, ctx.bodies);
    const Quat difference =
        worldFrame1(joint, ctx.bodies) * worldFrame0(joint, ctx.bodies).conjugate();
    applyWeldCorrection(ctx, joint.body0, joint.body1, anchors.p1 - anchors.p0, anchors.r0,
                        anchors.r1, rotationVector(difference), joint.compliance,
                        joint.lambdaPoint, joint.lambdaRotation, joint.linearImpulse,
                        joint.angularImpulse);
}

JointEvaluation evaluateFixedJoint(const Joint& joint, const Body* bodies) {
    const JointAnchors anchors = jointAnchors(joint, bodies);
    const double violation = (anchors.p1 - anchors.p0).norm();
    return {.error = violation, .elasticEnergy = elasticEnergy(violation, joint.compliance)};
}

}  // namespace substep
