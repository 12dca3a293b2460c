#pragma once
/// Joint definitions and the runtime record every joint type shares. Each type's solve
/// functions live in their own file (distance_joint.cpp, hinge_joint.cpp, ...), built on the two
/// correction operations of correction.h.
///
/// Conventions (ERRATA item 1 fixes the paper's mixed signs this way): body 0 is the paper's
/// body 1, body 1 its body 2. A correction is the motion body 0 must make relative to body 1 to
/// satisfy the constraint; λ then comes out non-negative for a stretched spring and the force is
/// λ/h² along the correction. A joint's angle is the right-hand rotation of body 1 relative to
/// body 0 about the joint axis.

#include "physics/handles.h"
#include "physics/math.h"

#include <cstdint>
#include <optional>

namespace substep {

enum class JointType : uint8_t { Distance, Fixed, Hinge, Spherical, Prismatic };

struct Range {
    double lower = 0.0;
    double upper = 0.0;
};

/// Creation settings. A null body means the world: its anchor and axes are then in world
/// coordinates. Anchors and axes of a body are in its user frame.
struct JointDef {
    JointType type = JointType::Distance;
    BodyId body0;
    BodyId body1;
    Vec3 anchor0 = Vec3::Zero();
    Vec3 anchor1 = Vec3::Zero();
    Vec3 axis0 = Vec3::UnitY();  ///< joint axis a
    Vec3 axis1 = Vec3::UnitY();
    /// Joint normal b (the zero angle is where the normals line up); missing means the same
    /// fixed perpendicular of the axis on both sides.
    std::optional<Vec3> normal0;
    std::optional<Vec3> normal1;
    double compliance = 0.0;  ///< attachment (m/N)

    double maxDistance = 0.0;  ///< distance: rope length; 0 attaches (a spring if compliant)

    std::optional<Range> limits;  ///< hinge: angle (rad); prismatic: offset along the axis (m)
    double limitCompliance = 0.0;
    std::optional<double> targetAngle;     ///< hinge drive
    std::optional<double> targetOffset;    ///< prismatic drive
    std::optional<double> targetVelocity;  ///< hinge motor (rad/s): advances the target angle
    double driveCompliance = 0.0;

    std::optional<double> swingLimit;   ///< spherical: largest angle between the axes
    std::optional<Range> twistLimits;   ///< spherical: twist about the axes
    std::optional<double> twistCompliance;  ///< spherical: twist limit compliance (default: limitCompliance)

    double linearDamping = 0.0;   ///< Eq. 31 (1/s)
    double angularDamping = 0.0;  ///< Eq. 32 (1/s)
    bool collide = false;         ///< whether the joined bodies still collide
};

/// A joint as the solver keeps it: body indices, anchors and frames in the bodies' principal
/// frames, parameters, and per-substep multipliers and impulses for force readout.
struct Joint {
    JointType type = JointType::Distance;
    uint32_t body0 = 0;  ///< body index; the world is the static body at index 0
    uint32_t body1 = 0;
    Vec3 anchor0 = Vec3::Zero();  ///< principal-frame anchor on body 0 (world point for the world)
    Vec3 anchor1 = Vec3::Zero();
    Quat frame0 = Quat::Identity();  ///< joint frame on body 0: columns a, b, c in its principal frame
    Quat frame1 = Quat::Identity();
    double compliance = 0.0;
    double maxDistance = 0.0;
    bool hasLimits = false;
    Range limits;
    double limitCompliance = 0.0;
    enum class Drive : uint8_t { None, Position, Velocity } drive = Drive::None;
    double target = 0.0;  ///< target angle or offset (a motor advances it each substep)
    double targetVelocity = 0.0;
    double driveCompliance = 0.0;
    bool hasSwingLimit = false;
    double swingLimit = 0.0;
    bool hasTwistLimits = false;
    Range twistLimits;
    double twistCompliance = 0.0;
    double linearDamping = 0.0;
    double angularDamping = 0.0;
    bool collide = false;
    bool alive = false;
    uint32_t generation = 0;

    // Runtime: one λ per part, zeroed each substep.
    Vec3 lambdaPoint = Vec3::Zero();  ///< attachment (vector multiplier, applyPointCorrection)
    Vec3 lambdaRotation = Vec3::Zero();  ///< orientation lock, weld or hinge axis alignment
    double lambdaAttach = 0.0;
    double lambdaLimit = 0.0;
    double lambdaTwist = 0.0;
    double lambdaDrive = 0.0;
    /// Sum of the positional (angular) correction impulses of the current substep:
    /// force = |linearImpulse| / h² (Eq. 10), torque = |angularImpulse| / h² (Eq. 17).
    Vec3 linearImpulse = Vec3::Zero();
    Vec3 angularImpulse = Vec3::Zero();

    void resetMultipliers() {
        lambdaPoint.setZero();
        lambdaRotation.setZero();
        lambdaAttach = lambdaLimit = lambdaTwist = lambdaDrive = 0.0;
        linearImpulse.setZero();
        angularImpulse.setZero();
    }
};

/// What a joint reports: force and torque magnitudes of the last substep, positional error (m),
/// and the elastic energy stored in its compliant parts (C²/2α) on the current state.
struct JointReadout {
    double force = 0.0;
    double torque = 0.0;
    double error = 0.0;
    double elasticEnergy = 0.0;
    /// The joint's coordinate on the current state: a hinge's angle (rad), a prismatic joint's
    /// offset along its axis (m), a spherical joint's swing, the angle between its axes (rad);
    /// 0 for distance and fixed joints.
    double coordinate = 0.0;
};

}  // namespace substep
