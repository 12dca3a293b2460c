// Distance joint: attachment, zero-rest-length spring and rope (paper 3.4.2, Eq. 25).
//
//   Δr = p1 − p0, the offset of body 1's anchor from body 0's.
//   Attachment / spring (d_max = 0):  Δx = Δr, compliance α makes it a spring of stiffness 1/α.
//   Rope (d_max > 0): only when |Δr| > d_max,  Δx = Δr/|Δr| (|Δr| − d_max)   (Eq. 25)
//   The attachment is projected with its full 3 x 3 inverse mass (applyPointCorrection); the
//   taut rope is a true scalar constraint along Δr and uses the scalar correction.
//   The correction moves body 0's anchor along Δx (ERRATA item 1), so a stretched joint has
//   λ > 0 and pulls with f = λ/h² (Eq. 10). Coincident anchors give Δr = 0: nothing to correct.

#include "physics/joints/joint_geometry.h"
#include "physics/joints/joint_rows.h"

namespace substep {
namespace {

/// The correction Δx and the violation |Δx| of a distance joint on the current state.
Vec3 distanceCorrection(const DistanceJoint& distance, const JointAnchors& anchors) {
    const Vec3 offset = anchors.p1 - anchors.p0;
    if (distance.maxDistance <= 0.0) return offset;
    const double length = offset.norm();
    if (length <= distance.maxDistance) return Vec3::Zero();  // slack rope
    // Eq. 25: Δx = Δr/|Δr| (|Δr| − d_max).
    return offset * ((length - distance.maxDistance) / length);
}

}  // namespace

void solveDistanceJoint(const Joint& joint, DistanceJoint& distance, SolverContext& ctx) {
    if (distance.maxDistance <= 0.0)
        return distance.attachment.solve(ctx, joint.body0, joint.body1, joint.anchor0, joint.anchor1,
                                         joint.compliance);
    const JointAnchors anchors = jointAnchors(joint, ctx.bodies);
    distance.rope.solve(ctx, joint.body0, joint.body1, distanceCorrection(distance, anchors), anchors.r0,
                        anchors.r1, joint.compliance);
}

void appendDistanceRows(const Joint& joint, DistanceJoint& distance, const SolverContext& ctx, JointRows& rows) {
    const JointAnchors anchors = jointAnchors(joint, ctx.bodies);
    if (distance.maxDistance <= 0.0) {
        Vec3 arm0, arm1;
        attachmentArms(joint, ctx, arm0, arm1);
        rows.addPoint(joint, distance.attachment, anchors.p1 - anchors.p0, arm0, arm1, joint.compliance);
        return;
    }
    // The rope only pulls (an inequality row), listed when taut or within kLimitMargin of it
    // (joint_rows.h says why); slack beyond that, it has no row at all.
    const Vec3 offset = anchors.p1 - anchors.p0;
    const double length = offset.norm();
    if (length < distance.maxDistance - kLimitMargin || !(length > kDirectionEpsilon)) return;
    rows.addAxis(joint, distance.rope, offset / length, length - distance.maxDistance, anchors.r0, anchors.r1,
                 joint.compliance, /*inequality=*/true);
}

JointEvaluation evaluateDistanceJoint(const Joint& joint, const DistanceJoint& distance, const Body* bodies) {
    const double violation = distanceCorrection(distance, jointAnchors(joint, bodies)).norm();
    return {.error = violation, .elasticEnergy = elasticEnergy(violation, joint.compliance)};
}

}  // namespace substep
