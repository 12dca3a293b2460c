#pragma once
/// A joint's anchors and frames on the bodies' current state, and the functions each joint
/// type's file defines (solve, evaluate), which joint_solver.cpp dispatches to.

#include "physics/correction.h"
#include "physics/joints/joint.h"

#include <cmath>

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

/// atan(t) / t as a polynomial in t² (the Taylor series through t¹⁵), for t² ≤ 0.01. Grouped in
/// pairs (Estrin's scheme) rather than nested (Horner's): the angle of a joint's part is on the
/// chain each joint waits for, and the pairs take three products and sums in sequence instead of
/// seven.
inline double atanSeries(double t2) {
    const double t4 = t2 * t2;
    const double low = (1.0 - t2 * (1.0 / 3)) + t4 * (1.0 / 5 - t2 * (1.0 / 7));
    const double high = (1.0 / 9 - t2 * (1.0 / 11)) + t4 * (1.0 / 13 - t2 * (1.0 / 15));
    return low + (t4 * t4) * high;
}

/// Column 0 of the rotation matrix of the unit quaternion f: a joint frame's axis a, in the
/// frame's parent coordinates, without building the rest of the matrix.
inline Vec3 frameAxis(const Quat& f) {
    return {1.0 - 2.0 * (f.y() * f.y() + f.z() * f.z()), 2.0 * (f.x() * f.y() + f.w() * f.z()),
            2.0 * (f.x() * f.z() - f.w() * f.y())};
}
/// Column 1 of the rotation matrix of the unit quaternion f: a joint frame's normal b.
inline Vec3 frameNormal(const Quat& f) {
    return {2.0 * (f.x() * f.y() - f.w() * f.z()), 1.0 - 2.0 * (f.x() * f.x() + f.z() * f.z()),
            2.0 * (f.y() * f.z() + f.w() * f.x())};
}

/// atan2(s, c): by its Taylor series in t = s/c where c > 0 and |s| ≤ c/10 (the odd terms
/// through t¹⁵, whose remainder is below 1e-17 of the result, so the two agree to rounding),
/// by std::atan2 elsewhere. A joint's angles are mostly small, and the series costs a division
/// and eight multiply-adds where std::atan2 takes several times as long.
inline double jointAtan2(double s, double c) {
    if (!(c > 0.0) || !(std::abs(s) <= 0.1 * c)) return std::atan2(s, c);
    const double t = s / c;
    return t * atanSeries(t * t);
}

/// rotationBetween (math.h) with jointAtan2's series for small angles, where it needs neither
/// the square root of |from × to| nor an arctangent: the rotation vector (axis times angle)
/// turning unit vector `from` onto unit vector `to` the short way.
inline Vec3 jointRotationBetween(const Vec3& from, const Vec3& to) {
    const Vec3 axis = from.cross(to);  // |axis| = sin θ
    const double c = from.dot(to);     // cos θ
    const double s2 = axis.squaredNorm();
    if (!(c > 0.0) || !(s2 <= 0.01 * c * c)) return rotationBetween(from, to);
    // θ / sin θ = atan(t) / (t c) with t = tan θ.
    const double inverseC = 1.0 / c;
    return axis * (atanSeries(s2 * inverseC * inverseC) * inverseC);
}

/// The rotation matrices of a joint's two bodies on their current orientations. A joint part
/// computes them once and shares them between its geometry (axes, normals, lever arms) and its
/// correction's inverse inertias; after a part has moved the bodies the next one takes new ones.
struct JointRotations {
    Mat3 r0, r1;
    JointRotations(const Joint& joint, const Body* bodies)
        : r0(bodies[joint.body0].q.toRotationMatrix()), r1(bodies[joint.body1].q.toRotationMatrix()) {}
};

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
