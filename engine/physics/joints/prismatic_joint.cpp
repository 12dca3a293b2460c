// Prismatic joint (paper 3.4.2): body 1 slides along body 0's joint axis a; the orientations
// are locked (hard, as the fixed joint's).
//
//   Δr = p1 − p0 in body 0's joint frame [a, b, c]:
//   off-axis:  Δx = b (Δr·b) + c (Δr·c), with the attachment compliance;
//   limits:    Δx = a (Δr·a − lower) below, a (Δr·a − upper) above, with the limit compliance;
//   drive:     Δx = a (Δr·a − target), with the drive compliance (Eq. 25 with d_target;
//              α = 1/k makes it a spring of stiffness k about the target offset).
//   The paper folds all limits into one projection; here the parts keep separate compliances
//   and multipliers, so a soft limit and a hard attachment can coexist.

#include "physics/joints/joint_geometry.h"
#include "physics/joints/joint_rows.h"

namespace substep {
namespace {

struct SlideState {
    Vec3 axis;
    double offset;   ///< Δr·a
    Vec3 offAxis;    ///< Δr minus its a-component
};

SlideState slideState(const Joint& joint, const Body* bodies, const JointAnchors& anchors) {
    const Vec3 axis = worldFrame0(joint, bodies) * Vec3::UnitX();
    const Vec3 offset = anchors.p1 - anchors.p0;
    const double along = offset.dot(axis);
    return {axis, along, offset - along * axis};
}

/// The joint's anchors with body 0's taken at the point of body 0 that body 1's anchor is
/// sliding over (p1), not at body 0's own anchor: the corrections act where the bodies meet.
/// With p0's lever arm, two bars sliding apart at 1 m/s gained energy without bound.
JointAnchors slidingAnchors(const Joint& joint, const Body* bodies) {
    JointAnchors anchors = jointAnchors(joint, bodies);
    anchors.r0 = anchors.p1 - bodies[joint.body0].x;
    return anchors;
}

double limitExcess(const PrismaticJoint& prismatic, double offset) {
    if (!prismatic.hasLimits) return 0.0;
    if (offset < prismatic.limits.lower) return offset - prismatic.limits.lower;
    if (offset > prismatic.limits.upper) return offset - prismatic.limits.upper;
    return 0.0;
}

}  // namespace

void solvePrismaticJoint(const Joint& joint, PrismaticJoint& prismatic, SolverContext& ctx) {
    {
        // Hard orientation lock: Eq. 18 on the joint frames, Eq. 19 with the exact angle.
        const Quat difference = worldFrame1(joint, ctx.bodies) * worldFrame0(joint, ctx.bodies).conjugate();
        prismatic.orientation.solve(ctx, joint.body0, joint.body1, rotationVector(difference), 0.0);
    }
    {
        const JointAnchors anchors = slidingAnchors(joint, ctx.bodies);
        const SlideState s = slideState(joint, ctx.bodies, anchors);
        prismatic.offAxis.solve(ctx, joint.body0, joint.body1, s.offAxis, anchors.r0, anchors.r1,
                                joint.compliance);
    }
    if (prismatic.hasLimits) {
        const JointAnchors anchors = slidingAnchors(joint, ctx.bodies);
        const SlideState s = slideState(joint, ctx.bodies, anchors);
        const double excess = limitExcess(prismatic, s.offset);
        if (excess != 0.0)
            prismatic.limit.solve(ctx, joint.body0, joint.body1, s.axis * excess, anchors.r0,
                                  anchors.r1, prismatic.limitCompliance);
    }
    if (prismatic.drive == JointDrive::Position) {
        const JointAnchors anchors = slidingAnchors(joint, ctx.bodies);
        const SlideState s = slideState(joint, ctx.bodies, anchors);
        // Eq. 25 with d_target: the offset along the axis pulled to the target.
        prismatic.drivePart.solve(ctx, joint.body0, joint.body1, s.axis * (s.offset - prismatic.target),
                                  anchors.r0, anchors.r1, prismatic.driveCompliance);
    }
}

void appendPrismaticRows(const Joint& joint, PrismaticJoint& prismatic, const SolverContext& ctx, JointRows& rows) {
    const Mat3 f0 = worldFrame0(joint, ctx.bodies).toRotationMatrix();
    const Vec3 rotation = rotationVector(worldFrame1(joint, ctx.bodies) * worldFrame0(joint, ctx.bodies).conjugate());
    for (int k = 0; k < 3; ++k) rows.addRotation(joint, prismatic.orientation, Vec3::Unit(k), rotation[k], 0.0);
    const JointAnchors anchors = slidingAnchors(joint, ctx.bodies);
    const SlideState s = slideState(joint, ctx.bodies, anchors);
    // Off the axis: the two directions of body 0's joint frame normal to it.
    for (int k = 1; k < 3; ++k)
        rows.addAxis(joint, prismatic.offAxis, f0.col(k), s.offAxis.dot(f0.col(k)), anchors.r0, anchors.r1,
                     joint.compliance, /*inequality=*/false);
    if (prismatic.hasLimits) {
        // The bound the offset is beyond or within kLimitMargin of (joint_rows.h says why).
        const double belowLower = prismatic.limits.lower - s.offset;
        const double aboveUpper = s.offset - prismatic.limits.upper;
        if (belowLower > -kLimitMargin && belowLower >= aboveUpper)
            rows.addAxis(joint, prismatic.limit, -s.axis, belowLower, anchors.r0, anchors.r1,
                         prismatic.limitCompliance, /*inequality=*/true);
        else if (aboveUpper > -kLimitMargin)
            rows.addAxis(joint, prismatic.limit, s.axis, aboveUpper, anchors.r0, anchors.r1,
                         prismatic.limitCompliance, /*inequality=*/true);
    }
    if (prismatic.drive == JointDrive::Position)  // Eq. 25 with d_target
        rows.addAxis(joint, prismatic.drivePart, s.axis, s.offset - prismatic.target, anchors.r0, anchors.r1,
                     prismatic.driveCompliance, /*inequality=*/false);
}

JointEvaluation evaluatePrismaticJoint(const Joint& joint, const PrismaticJoint& prismatic,
                                       const Body* bodies) {
    const SlideState s = slideState(joint, bodies, jointAnchors(joint, bodies));
    const double offAxis = s.offAxis.norm();
    const double excess = std::abs(limitExcess(prismatic, s.offset));
    double energy = elasticEnergy(offAxis, joint.compliance) +
                    elasticEnergy(excess, prismatic.limitCompliance);
    if (prismatic.drive == JointDrive::Position)
        energy += elasticEnergy(s.offset - prismatic.target, prismatic.driveCompliance);
    return {.error = offAxis + excess, .elasticEnergy = energy};
}

}  // namespace substep
