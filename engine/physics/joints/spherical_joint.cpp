// Spherical (ball-in-socket) joint (paper 3.4.1, Eq. 22, Eq. 23, Eq. 24): free rotation about the anchor,
// with optional swing and twist limits that are decoupled.
//
//   Swing: the angle between the axes a0 and a1, limited to [0, swing] by Algorithm 3 with
//   [n, n0, n1] = [a0 × a1 / |a0 × a1|, a0, a1]. Parallel axes need no swing correction;
//   anti-parallel axes have no unique swing plane, so any perpendicular of a0 is used.
//   Twist: about n = (a0 + a1)/|a0 + a1| (Eq. 22), between the normals with their n-component
//   removed and then normalised (Eq. 23, Eq. 24, ERRATA item 5). Twist is undefined when the axes
//   are anti-parallel (a0 + a1 = 0) or a normal lies along n; the twist limit waits until the
//   swing brings the axes back below about 177°.
//   Position: the attachment Δx = p1 − p0.

#include "physics/correction_kernels.h"
#include "physics/joints/joint_geometry.h"
#include "physics/joints/joint_rows.h"

namespace substep {
namespace {

/// Unit swing axis n and whether a swing correction can be needed at all; `angle` is then the
/// swing, the angle from a0 to a1 about n (Algorithm 3's φ, in [0, π]).
bool swingAxis(const Vec3& a0, const Vec3& a1, Vec3& n, double& angle) {
    const Vec3 cross = a0.cross(a1);
    const double length = cross.norm();
    const double c = a0.dot(a1);
    if (length > kDirectionEpsilon) {
        n = cross / length;
        angle = jointAtan2(length, c);  // (a0 × a1) · n = |a0 × a1|
        return true;
    }
    if (c > 0.0) return false;  // aligned
    n = anyPerpendicular(a0);   // anti-parallel: swing is π in every plane
    angle = M_PI;
    return true;
}
bool swingAxis(const Vec3& a0, const Vec3& a1, Vec3& n) {
    double angle;
    return swingAxis(a0, a1, n, angle);
}

/// |a0 + a1| below which twist is treated as undefined (a swing beyond about 177°).
constexpr double kTwistUndefinedBelow = 0.05;

/// Twist axis (Eq. 22) and the two projected normals (Eq. 23, Eq. 24); false where twist is
/// undefined.
bool twistFrame(const Mat3& f0, const Mat3& f1, Vec3& n, Vec3& n0, Vec3& n1) {
    n = f0.col(0) + f1.col(0);  // Eq. 22
    const double length = n.norm();
    // Near a half-turn swing n swings round faster than any substep can follow (a swing within
    // 1e-3 of 180° turned 9.8 J into 1.7 MJ): twist is left alone beyond about 177°.
    if (length < kTwistUndefinedBelow) return false;
    n /= length;
    n0 = f0.col(1) - n.dot(f0.col(1)) * n;  // Eq. 23
    n1 = f1.col(1) - n.dot(f1.col(1)) * n;  // Eq. 24
    const double l0 = n0.norm();
    const double l1 = n1.norm();
    if (l0 < 1e-9 || l1 < 1e-9) return false;
    n0 /= l0;  // Eq. 23's "n1 ← |n1|": normalised (ERRATA item 5)
    n1 /= l1;  // Eq. 24 likewise
    return true;
}

/// The twist axis n (Eq. 22) and the twist angle between the normals projected onto the plane
/// normal to it (Eq. 23, Eq. 24), for the solve: atan2((n0 × n1) · n, n0 · n1) does not depend on
/// the projected normals' lengths, so they are not normalised (two square roots and divisions
/// fewer than twistFrame, whose unit normals the block rows and the readout use). False where
/// twist is undefined, as for twistFrame.
bool twistAngle(const Vec3& a0, const Vec3& b0, const Vec3& a1, const Vec3& b1, Vec3& n, double& angle) {
    n = a0 + a1;  // Eq. 22
    const double length = n.norm();
    if (length < kTwistUndefinedBelow) return false;
    n /= length;
    const Vec3 n0 = b0 - n.dot(b0) * n;  // Eq. 23, unnormalised
    const Vec3 n1 = b1 - n.dot(b1) * n;  // Eq. 24, unnormalised
    if (n0.squaredNorm() < 1e-18 || n1.squaredNorm() < 1e-18) return false;  // twistFrame's 1e-9 lengths
    angle = jointAtan2(n0.cross(n1).dot(n), n0.dot(n1));
    return true;
}

/// AnglePart::solveLimit with its angular correction inlined (correction_kernels.h) and taken
/// about the unit axis n by the excess directly: a rope's joints run two limits and an
/// attachment each, every one waiting on the previous one's turn.
inline void solveAngleLimit(AnglePart& part, SolverContext& ctx, const Joint& joint, const JointRotations& rotations,
                            const Vec3& n, double phi, double lower, double upper, double compliance) {
    // The turn is |excess| about ±n (n is unit).
    const double excess = limitExcess(phi, lower, upper);
    if (excess != 0.0)
        part.impulse += correction_kernels::axisCorrection(ctx, joint.body0, joint.body1, rotations.r0, rotations.r1,
                                                           excess < 0.0 ? Vec3(-n) : n, std::abs(excess), compliance,
                                                           part.lambda);
}

}  // namespace

void solveSphericalJoint(const Joint& joint, SphericalJoint& spherical, SolverContext& ctx) {
    // Each limit measures its frames with the rotation matrices its correction's inverse
    // inertias are built from; the axes and normals in the bodies' principal frames are the
    // joint frames' first two columns.
    if (spherical.hasSwingLimit) {
        const JointRotations rotations(joint, ctx.bodies);
        const Vec3 a0 = rotations.r0 * frameAxis(joint.frame0);
        const Vec3 a1 = rotations.r1 * frameAxis(joint.frame1);
        Vec3 n;
        double swing;
        if (swingAxis(a0, a1, n, swing))
            solveAngleLimit(spherical.swing, ctx, joint, rotations, n, swing, -spherical.swingLimit,
                            spherical.swingLimit, spherical.swingCompliance);
    }
    if (spherical.hasTwistLimits) {
        const JointRotations rotations(joint, ctx.bodies);
        Vec3 n;
        double twist;
        if (twistAngle(rotations.r0 * frameAxis(joint.frame0), rotations.r0 * frameNormal(joint.frame0),
                       rotations.r1 * frameAxis(joint.frame1), rotations.r1 * frameNormal(joint.frame1), n, twist))
            solveAngleLimit(spherical.twist, ctx, joint, rotations, n, twist, spherical.twistLimits.lower,
                            spherical.twistLimits.upper, spherical.twistCompliance);
    }
    // PointPart::solve, inlined likewise.
    PointPart& attachment = spherical.attachment;
    attachment.impulse += correction_kernels::attachmentCorrection(ctx, joint.body0, joint.body1, joint.anchor0,
                                                                   joint.anchor1, joint.compliance, attachment.lambda);
}

void appendSphericalRows(const Joint& joint, SphericalJoint& spherical, const SolverContext& ctx, JointRows& rows) {
    if (spherical.hasSwingLimit || spherical.hasTwistLimits) {
        const Mat3 f0 = worldFrame0(joint, ctx.bodies).toRotationMatrix();
        const Mat3 f1 = worldFrame1(joint, ctx.bodies).toRotationMatrix();
        Vec3 n, n0, n1;
        if (spherical.hasSwingLimit && swingAxis(f0.col(0), f1.col(0), n))
            rows.addAngleLimit(joint, spherical.swing, n, f0.col(0), f1.col(0), -spherical.swingLimit,
                               spherical.swingLimit, spherical.swingCompliance);
        if (spherical.hasTwistLimits && twistFrame(f0, f1, n, n0, n1))
            rows.addAngleLimit(joint, spherical.twist, n, n0, n1, spherical.twistLimits.lower,
                               spherical.twistLimits.upper, spherical.twistCompliance);
    }
    const JointAnchors anchors = jointAnchors(joint, ctx.bodies);
    Vec3 arm0, arm1;
    attachmentArms(joint, ctx, arm0, arm1);
    rows.addPoint(joint, spherical.attachment, anchors.p1 - anchors.p0, arm0, arm1, joint.compliance);
}

JointEvaluation evaluateSphericalJoint(const Joint& joint, const SphericalJoint& spherical, const Body* bodies) {
    const JointAnchors anchors = jointAnchors(joint, bodies);
    const double gap = (anchors.p1 - anchors.p0).norm();
    double energy = elasticEnergy(gap, joint.compliance);
    const Mat3 f0 = worldFrame0(joint, bodies).toRotationMatrix();
    const Mat3 f1 = worldFrame1(joint, bodies).toRotationMatrix();
    if (spherical.hasSwingLimit) {
        Vec3 n;
        if (swingAxis(f0.col(0), f1.col(0), n))
            energy += elasticEnergy(angleLimitViolation(n, f0.col(0), f1.col(0),
                                                        -spherical.swingLimit, spherical.swingLimit),
                                    spherical.swingCompliance);
    }
    if (spherical.hasTwistLimits) {
        Vec3 n, n0, n1;
        if (twistFrame(f0, f1, n, n0, n1))
            energy += elasticEnergy(angleLimitViolation(n, n0, n1, spherical.twistLimits.lower,
                                                        spherical.twistLimits.upper),
                                    spherical.twistCompliance);
    }
    return {.error = gap, .elasticEnergy = energy};
}

}  // namespace substep
