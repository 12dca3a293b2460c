#pragma once
/// A joint's anchors and frames on the bodies' current state, and the functions each joint
/// type's file defines (solve, evaluate), which joint_solver.cpp dispatches to.

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

/// What a type's evaluation reports on the current state.
struct JointEvaluation {
    double error = 0.0;          ///< positional violation (m)
    double elasticEnergy = 0.0;  ///< J
};

// Per-type solve and evaluation functions (one file each): `joint` holds the shared data,
// the second argument is its model (joint.model's alternative).
void solveDistanceJoint(const Joint& joint, DistanceJoint& distance, SolverContext& ctx);
void solveFixedJoint(const Joint& joint, FixedJoint& fixed, SolverContext& ctx);
void solveHingeJoint(const Joint& joint, HingeJoint& hinge, SolverContext& ctx);
void solveSphericalJoint(const Joint& joint, SphericalJoint& spherical, SolverContext& ctx);
void solvePrismaticJoint(const Joint& joint, PrismaticJoint& prismatic, SolverContext& ctx);

struct JointRows;
// Per-type rows for the block solve (joint_rows.h), from the same geometry as the type's solve.
void appendDistanceRows(const Joint& joint, DistanceJoint& distance, const SolverContext& ctx, JointRows& rows);
void appendFixedRows(const Joint& joint, FixedJoint& fixed, const SolverContext& ctx, JointRows& rows);
void appendHingeRows(const Joint& joint, HingeJoint& hinge, const SolverContext& ctx, JointRows& rows);
void appendSphericalRows(const Joint& joint, SphericalJoint& spherical, const SolverContext& ctx, JointRows& rows);
void appendPrismaticRows(const Joint& joint, PrismaticJoint& prismatic, const SolverContext& ctx, JointRows& rows);

/// The lever arms of a joint's attachment for a correction's Jacobian: on the poses
/// directionOrientation names (the current ones, or the substep's start).
inline void attachmentArms(const Joint& joint, const SolverContext& ctx, Vec3& arm0, Vec3& arm1) {
    arm0 = directionOrientation(ctx, ctx.bodies[joint.body0]) * joint.anchor0;
    arm1 = directionOrientation(ctx, ctx.bodies[joint.body1]) * joint.anchor1;
}

JointEvaluation evaluateDistanceJoint(const Joint& joint, const DistanceJoint& distance, const Body* bodies);
JointEvaluation evaluateFixedJoint(const Joint& joint, const FixedJoint& fixed, const Body* bodies);
JointEvaluation evaluateHingeJoint(const Joint& joint, const HingeJoint& hinge, const Body* bodies);
JointEvaluation evaluateSphericalJoint(const Joint& joint, const SphericalJoint& spherical, const Body* bodies);
JointEvaluation evaluatePrismaticJoint(const Joint& joint, const PrismaticJoint& prismatic, const Body* bodies);

/// The hinge angle (rad, right-hand rule about body 0's axis) of body 1 relative to body 0.
double hingeAngle(const Joint& joint, const Body* bodies);

}  // namespace substep
