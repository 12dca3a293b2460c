// Hinge joint (paper 3.4.1): one rotational degree of freedom about the joint axis a.
//
//   Axis alignment (Eq. 20): body 0 turns by the rotation taking a0 onto a1 (hard), solved over
//   the two directions normal to the axis at once (block form). The exact
//   angle is used instead of |a0 × a1| = sin θ, and anti-parallel axes (a0 + a1 = 0, no unique
//   axis) turn about any perpendicular instead of producing a zero or NaN correction.
//   Angle φ: the angle from b0 to b1 about a0, positive when body 1 turns counter-clockwise
//   relative to body 0 (right-hand rule).
//   Drive (Eq. 21): b_target = rot(a0, α) b0; body 0 turns by the rotation taking b_target onto
//   b1, with the drive compliance. A velocity motor advances α by h·v every substep.
//   Limits: Algorithm 3 with [n, n0, n1] = [a0, b0, b1] (ERRATA items 3-4).
//   Drive and limits use b1 projected onto the plane normal to a0 (as Eq. 23 and Eq. 24 do for twist),
//   so their corrections turn about a0 alone. Taken as it is, b1 carries the axis misalignment
//   the alignment part has yet to remove, and the correction then also turns about an axis in the
//   hinge plane, where a thin bar's inertia is tiny: alignment and drive fight every substep and
//   pump energy into a spin about the bar's long axis (a bar resting on a limit 0.5 rad from level
//   reached 1700 rad/s before this projection).
//   Position: the attachment Δx = p1 − p0.

#include "physics/joints/joint_geometry.h"
#include "physics/joints/joint_rows.h"

namespace substep {

namespace {

/// Body 1's normal b1 with its component along the unit axis a0 removed, normalised; false
/// when b1 lies along a0 (the axes are then 90° apart and the angle is undefined).
bool normalInHingePlane(const Vec3& a0, const Vec3& b1, Vec3& projected) {
    projected = b1 - b1.dot(a0) * a0;
    const double length = projected.norm();
    if (length < 1e-9) return false;
    projected /= length;
    return true;
}

}  // namespace

double hingeAngle(const Joint& joint, const Body* bodies) {
    const Mat3 f0 = worldFrame0(joint, bodies).toRotationMatrix();
    const Mat3 f1 = worldFrame1(joint, bodies).toRotationMatrix();
    return signedAngle(f0.col(0), f0.col(1), f1.col(1));
}

void solveHingeJoint(const Joint& joint, HingeJoint& hinge, SolverContext& ctx) {
    const Body& body0 = ctx.bodies[joint.body0];
    const Body& body1 = ctx.bodies[joint.body1];
    // The axes a0, a1 in the bodies' principal frames; each part turns them into world axes
    // with the rotation matrices its correction's inverse inertias are built from.
    const Vec3 axis0 = frameAxis(joint.frame0);
    const Vec3 axis1 = frameAxis(joint.frame1);
    {
        const JointRotations rotations(joint, ctx.bodies);
        const Vec3 a0 = rotations.r0 * axis0;
        const Vec3 a1 = rotations.r1 * axis1;
        const Vec3 rotation = jointRotationBetween(a0, a1);  // Eq. 20, with the exact angle
        // Block form over the two directions normal to the hinge axis, so the alignment never
        // turns the hinge itself (applyRotationCorrection, which takes the axis unnormalised).
        const Vec3 sum = a0 + a1;
        Vec3 free = sum.squaredNorm() > 1e-18 ? sum : a0;
        if (ctx.projection == JointProjection::Start) {
            // The constrained directions of the substep's start, as the inverse inertias are.
            const Mat3 start0 = directionRotation(ctx, body0, rotations.r0);
            const Mat3 start1 = directionRotation(ctx, body1, rotations.r1);
            const Vec3 s0 = start0 * axis0;
            const Vec3 s1 = start1 * axis1;
            if ((s0 + s1).squaredNorm() > 1e-18) free = s0 + s1;
            hinge.alignment.solve(ctx, joint.body0, joint.body1, start0, start1, rotation, 0.0, &free);
        } else {
            hinge.alignment.solve(ctx, joint.body0, joint.body1, rotations.r0, rotations.r1, rotation, 0.0, &free);
        }
    }
    Vec3 b1;
    if (hinge.drive != JointDrive::None) {
        const JointRotations rotations(joint, ctx.bodies);
        const Vec3 a0 = rotations.r0 * axis0;
        if (normalInHingePlane(a0, rotations.r1 * frameNormal(joint.frame1), b1)) {
            // Eq. 21: b_target = rot(a0, α) b0, turned onto b1.
            const Vec3 target = Eigen::AngleAxisd(hinge.target, a0) * (rotations.r0 * frameNormal(joint.frame0));
            hinge.drivePart.solve(ctx, joint.body0, joint.body1, rotations.r0, rotations.r1,
                                  rotationBetween(target, b1), hinge.driveCompliance);
        }
    }
    if (hinge.hasLimits) {
        const JointRotations rotations(joint, ctx.bodies);
        const Vec3 a0 = rotations.r0 * axis0;
        if (normalInHingePlane(a0, rotations.r1 * frameNormal(joint.frame1), b1))
            hinge.limit.solveLimit(ctx, joint.body0, joint.body1, rotations.r0, rotations.r1, a0,
                                   signedAngle(a0, rotations.r0 * frameNormal(joint.frame0), b1),
                                   hinge.limits.lower, hinge.limits.upper, hinge.limitCompliance);
    }
    hinge.attachment.solve(ctx, joint.body0, joint.body1, joint.anchor0, joint.anchor1, joint.compliance);
}

void appendHingeRows(const Joint& joint, HingeJoint& hinge, const SolverContext& ctx, JointRows& rows) {
    const Mat3 f0 = worldFrame0(joint, ctx.bodies).toRotationMatrix();
    const Mat3 f1 = worldFrame1(joint, ctx.bodies).toRotationMatrix();
    const Vec3 a0 = f0.col(0);
    const Vec3 a1 = f1.col(0);
    {
        // Eq. 20 over the two directions normal to the hinge axis (as solveHingeJoint).
        const Vec3 rotation = rotationBetween(a0, a1);
        Vec3 free = (a0 + a1).norm() > 1e-9 ? Vec3((a0 + a1).normalized()) : a0;
        if (ctx.projection == JointProjection::Start) {
            const Vec3 s0 = directionOrientation(ctx, ctx.bodies[joint.body0]) * joint.frame0 * Vec3::UnitX();
            const Vec3 s1 = directionOrientation(ctx, ctx.bodies[joint.body1]) * joint.frame1 * Vec3::UnitX();
            if ((s0 + s1).norm() > 1e-9) free = (s0 + s1).normalized();
        }
        const Vec3 u = anyPerpendicular(free);
        const Vec3 v = free.cross(u);
        rows.addRotation(joint, hinge.alignment, u, rotation.dot(u), 0.0);
        rows.addRotation(joint, hinge.alignment, v, rotation.dot(v), 0.0);
    }
    Vec3 b1;
    if ((hinge.drive != JointDrive::None || hinge.hasLimits) && normalInHingePlane(a0, f1.col(1), b1)) {
        if (hinge.drive != JointDrive::None) {
            // Eq. 21: body 0 turns about a0 by the angle from b_target to b1. The row stays in
            // the system at the target too, where it holds the angle against the other rows.
            const Vec3 target = Eigen::AngleAxisd(hinge.target, a0) * f0.col(1);
            rows.addAngle(joint, hinge.drivePart, a0, signedAngle(a0, target, b1), hinge.driveCompliance,
                          /*inequality=*/false);
        }
        if (hinge.hasLimits)
            rows.addAngleLimit(joint, hinge.limit, a0, f0.col(1), b1, hinge.limits.lower, hinge.limits.upper,
                               hinge.limitCompliance);
    }
    const JointAnchors anchors = jointAnchors(joint, ctx.bodies);
    Vec3 arm0, arm1;
    attachmentArms(joint, ctx, arm0, arm1);
    rows.addPoint(joint, hinge.attachment, anchors.p1 - anchors.p0, arm0, arm1, joint.compliance);
}

JointEvaluation evaluateHingeJoint(const Joint& joint, const HingeJoint& hinge, const Body* bodies) {
    const JointAnchors anchors = jointAnchors(joint, bodies);
    const double gap = (anchors.p1 - anchors.p0).norm();
    double energy = elasticEnergy(gap, joint.compliance);
    const double angle = hingeAngle(joint, bodies);
    if (hinge.drive != JointDrive::None)
        energy += elasticEnergy(wrapAngle(angle - hinge.target), hinge.driveCompliance);
    if (hinge.hasLimits) {
        const double excess = angle < hinge.limits.lower   ? hinge.limits.lower - angle
                              : angle > hinge.limits.upper ? angle - hinge.limits.upper
                                                           : 0.0;
        energy += elasticEnergy(excess, hinge.limitCompliance);
    }
    return {.error = gap, .elasticEnergy = energy};
}

}  // namespace substep
