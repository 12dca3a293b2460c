#pragma once
/// A joint's parts as linearised rows, for the direct (block) solve of joint clusters around
/// light bodies (physics/joint_block_solve.h). Each row is one scalar constraint of a part: a
/// positional row moves body 0's point at arm0 along `direction` relative to body 1's point at
/// arm1 (Eqs. 2-3's Jacobian), an angular row turns body 0 about `direction` relative to body 1
/// (Eqs. 11-12's). `violation` is the constraint value c that the correction must remove, on the
/// current state, with the sign convention of joint.h (a correction is the motion body 0 must
/// make relative to body 1, so λ ≥ 0 for a stretched spring).
///
/// Each joint type's file lists its rows (appendHingeRows, ...) beside its Gauss-Seidel solve,
/// from the same geometry; equality rows are listed even when they are satisfied, since a block
/// solve must hold them against the other rows, and inequality rows (limits, a taut rope) only
/// when they are violated.

#include "physics/correction.h"
#include "physics/joints/joint.h"

#include <array>
#include <cstdint>

namespace substep {

/// How close to an angle limit (rad) or a linear one (m) its row joins the block solve.
inline constexpr double kLimitMargin = 1e-3;

/// One scalar row of a joint part.
struct JointRow {
    Vec3 direction = Vec3::Zero();  ///< unit: the impulse's direction, or the rotation axis
    Vec3 arm0 = Vec3::Zero();       ///< positional rows: lever arm on body 0 (world)
    Vec3 arm1 = Vec3::Zero();       ///< positional rows: lever arm on body 1 (world)
    double violation = 0.0;         ///< c along the row
    double compliance = 0.0;        ///< α of the part
    bool angular = false;
    bool inequality = false;        ///< only pushes (λ ≥ 0): a limit or a taut rope
    uint32_t body0 = 0;
    uint32_t body1 = 0;
    /// The part's impulse this substep (JointPart::impulse), which is also its vector multiplier:
    /// the row's λ so far is impulse · direction.
    Vec3* impulse = nullptr;
    Vec3* vectorLambda = nullptr;    ///< PointPart, RotationPart
    double* scalarLambda = nullptr;  ///< AxisPart, AnglePart
};

/// At most this many rows in one cluster's system (a hinge has 7, a ball joint 3 to 5).
inline constexpr int kMaxBlockRows = 48;

/// The rows of one cluster, in fixed storage (nothing allocated per substep).
struct JointRows {
    std::array<JointRow, kMaxBlockRows> rows;
    int count = 0;
    /// False (and nothing added) when the storage is full.
    bool add(const JointRow& row) {
        if (count >= kMaxBlockRows) return false;
        rows[count++] = row;
        return true;
    }
    /// The three rows of an attachment (PointPart): world axes, violation delta = p1 − p0.
    void addPoint(const Joint& joint, PointPart& part, const Vec3& delta, const Vec3& arm0,
                  const Vec3& arm1, double compliance) {
        for (int k = 0; k < 3; ++k)
            add({.direction = Vec3::Unit(k), .arm0 = arm0, .arm1 = arm1, .violation = delta[k],
                 .compliance = compliance, .body0 = joint.body0, .body1 = joint.body1,
                 .impulse = &part.impulse, .vectorLambda = &part.lambda});
    }
    /// One positional row of a scalar part (AxisPart).
    void addAxis(const Joint& joint, AxisPart& part, const Vec3& direction, double violation,
                 const Vec3& arm0, const Vec3& arm1, double compliance, bool inequality) {
        add({.direction = direction, .arm0 = arm0, .arm1 = arm1, .violation = violation,
             .compliance = compliance, .inequality = inequality, .body0 = joint.body0,
             .body1 = joint.body1, .impulse = &part.impulse, .scalarLambda = &part.lambda});
    }
    /// One angular row of a scalar part (AnglePart).
    void addAngle(const Joint& joint, AnglePart& part, const Vec3& axis, double violation,
                  double compliance, bool inequality) {
        add({.direction = axis, .violation = violation, .compliance = compliance, .angular = true,
             .inequality = inequality, .body0 = joint.body0, .body1 = joint.body1,
             .impulse = &part.impulse, .scalarLambda = &part.lambda});
    }
    /// An angular row of a vector part (RotationPart) about unit `axis`, violation
    /// rotation · axis.
    void addRotation(const Joint& joint, RotationPart& part, const Vec3& axis, double violation,
                     double compliance) {
        add({.direction = axis, .violation = violation, .compliance = compliance, .angular = true,
             .body0 = joint.body0, .body1 = joint.body1, .impulse = &part.impulse,
             .vectorLambda = &part.lambda});
    }
    /// An angle limit (Algorithm 3) as an inequality row about ±n whose λ may only push back:
    /// for the bound the angle from n0 to n1 about n is beyond, or within kLimitMargin of. A
    /// body resting on its bound is then held by the row every substep; listed only once it is
    /// past the bound, the row would be missing in every other substep and the body would
    /// chatter on the stop. Inside the margin the violation is negative, and a row that would
    /// have to pull the body onto its bound is dropped by the solve's active-set loop.
    void addAngleLimit(const Joint& joint, AnglePart& part, const Vec3& n, const Vec3& n0,
                       const Vec3& n1, double lower, double upper, double compliance) {
        const double phi = signedAngle(n, n0, n1);
        if (phi < lower || phi > upper) {
            double excess = phi - (phi < lower ? lower : upper);
            if (excess > M_PI) excess -= 2.0 * M_PI;
            if (excess <= -M_PI) excess += 2.0 * M_PI;
            addAngle(joint, part, excess >= 0.0 ? n : Vec3(-n), std::abs(excess), compliance, true);
        } else if (phi - lower < kLimitMargin && phi - lower <= upper - phi) {
            addAngle(joint, part, -n, lower - phi, compliance, true);
        } else if (upper - phi < kLimitMargin) {
            addAngle(joint, part, n, phi - upper, compliance, true);
        }
    }
};

/// Upper bound of the rows a joint can list (for sizing clusters when they are built).
inline int maxJointRows(const Joint& joint) {
    switch (joint.type()) {
        case JointType::Distance: return 3;
        case JointType::Fixed: return 6;
        case JointType::Hinge: return 7;
        case JointType::Spherical: return 5;
        case JointType::Prismatic: return 7;
    }
    return 7;
}

/// Lists a joint's rows on the current state (lever arms and inverse inertias as
/// ctx.projection names them); joint_block_solve.cpp dispatches here.
void appendJointRows(Joint& joint, const SolverContext& ctx, JointRows& rows);

}  // namespace substep
