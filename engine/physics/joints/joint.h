#pragma once
/// Joint definitions and the runtime record: what every joint type shares, and each type's own
/// parameters and parts (joint_parts.h) in a variant. Each type's solve functions live in their
/// own file (distance_joint.cpp, hinge_joint.cpp, ...), built on the parts.
///
/// Conventions (ERRATA item 1 fixes the paper's mixed signs this way): body 0 is the paper's
/// body 1, body 1 its body 2. A correction is the motion body 0 must make relative to body 1 to
/// satisfy the constraint; λ then comes out non-negative for a stretched spring and the force is
/// λ/h² along the correction. A joint's angle is the right-hand rotation of body 1 relative to
/// body 0 about the joint axis.

#include "physics/handles.h"
#include "physics/joints/joint_parts.h"
#include "physics/math.h"

#include <cstdint>
#include <optional>
#include <tuple>
#include <variant>

namespace substep {

enum class JointType : uint8_t { Distance, Fixed, Hinge, Spherical, Prismatic };

/// The type's name as scene files spell it ("hinge", "spherical", ...).
constexpr const char* jointTypeName(JointType type) {
    switch (type) {
        case JointType::Distance:
            return "distance";
        case JointType::Fixed:
            return "fixed";
        case JointType::Hinge:
            return "hinge";
        case JointType::Spherical:
            return "spherical";
        case JointType::Prismatic:
            return "prismatic";
    }
    return "joint";
}

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

/// How a hinge or prismatic joint is driven.
enum class JointDrive : uint8_t { None, Position, Velocity };

// Each type's parameters and parts (Box2D keeps the former in a union, Jolt assembles a
// constraint from the latter). parts() lists the parts in the order the type solves them; the
// readout sums their impulses in that order.

/// Distance joint (distance_joint.cpp): attachment or spring, or a rope of length maxDistance.
struct DistanceJoint {
    double maxDistance = 0.0;  ///< rope length; 0 attaches (a spring if compliant)
    PointPart attachment;      ///< maxDistance = 0
    AxisPart rope;             ///< maxDistance > 0, Eq. 25
    auto parts() { return std::tie(attachment, rope); }
    auto parts() const { return std::tie(attachment, rope); }
};

/// Fixed joint (fixed_joint.cpp): attachment and orientation lock, solved as one weld.
struct FixedJoint {
    PointPart attachment;
    RotationPart orientation;
    auto parts() { return std::tie(orientation, attachment); }
    auto parts() const { return std::tie(orientation, attachment); }
};

/// Hinge joint (hinge_joint.cpp): axis alignment, drive or motor, angle limits, attachment.
struct HingeJoint {
    bool hasLimits = false;
    Range limits;                  ///< angle (rad)
    double limitCompliance = 0.0;
    JointDrive drive = JointDrive::None;
    double target = 0.0;           ///< target angle (a motor advances it each substep)
    double targetVelocity = 0.0;   ///< motor (rad/s)
    double driveCompliance = 0.0;
    RotationPart alignment;        ///< Eq. 20
    AnglePart drivePart;           ///< Eq. 21
    AnglePart limit;               ///< Algorithm 3
    PointPart attachment;
    auto parts() { return std::tie(alignment, drivePart, limit, attachment); }
    auto parts() const { return std::tie(alignment, drivePart, limit, attachment); }
};

/// Spherical joint (spherical_joint.cpp): swing and twist limits, attachment.
struct SphericalJoint {
    bool hasSwingLimit = false;
    double swingLimit = 0.0;       ///< largest angle between the axes (rad)
    double swingCompliance = 0.0;
    bool hasTwistLimits = false;
    Range twistLimits;             ///< twist about the axes (rad)
    double twistCompliance = 0.0;
    AnglePart swing;               ///< Algorithm 3 about a0 × a1
    AnglePart twist;               ///< Algorithm 3 about Eq. 22's axis, between Eq. 23's and Eq. 24's normals
    PointPart attachment;
    auto parts() { return std::tie(swing, twist, attachment); }
    auto parts() const { return std::tie(swing, twist, attachment); }
};

/// Prismatic joint (prismatic_joint.cpp): orientation lock, off-axis attachment, offset limits
/// and drive along the axis.
struct PrismaticJoint {
    bool hasLimits = false;
    Range limits;                  ///< offset along the axis (m)
    double limitCompliance = 0.0;
    JointDrive drive = JointDrive::None;  ///< Position only (a velocity drive does nothing)
    double target = 0.0;           ///< target offset (m)
    double driveCompliance = 0.0;
    RotationPart orientation;
    AxisPart offAxis;              ///< with the joint's compliance
    AxisPart limit;
    AxisPart drivePart;
    auto parts() { return std::tie(orientation, offAxis, limit, drivePart); }
    auto parts() const { return std::tie(orientation, offAxis, limit, drivePart); }
};

/// One alternative per JointType, in the enum's order (Joint::type() is the index).
using JointModel = std::variant<DistanceJoint, FixedJoint, HingeJoint, SphericalJoint, PrismaticJoint>;

/// Calls f with the joint model's alternative (a switch: no virtual call, nothing allocated),
/// inlined: the multipliers are reset through it for every joint every substep.
template <class Model, class F>
[[gnu::always_inline]] inline decltype(auto) visitJointModel(Model& model, F&& f) {
    switch (model.index()) {
        case 0: return f(*std::get_if<0>(&model));
        case 1: return f(*std::get_if<1>(&model));
        case 2: return f(*std::get_if<2>(&model));
        case 3: return f(*std::get_if<3>(&model));
        default: return f(*std::get_if<4>(&model));
    }
}

/// A joint as the solver keeps it: what every type shares (body indices, anchors and frames in
/// the bodies' principal frames, attachment compliance, damping) and the type's own parameters
/// and parts (`model`).
struct Joint {
    uint32_t body0 = 0;  ///< body index; the world is the static body at index 0
    uint32_t body1 = 0;
    Vec3 anchor0 = Vec3::Zero();  ///< principal-frame anchor on body 0 (world point for the world)
    Vec3 anchor1 = Vec3::Zero();
    Quat frame0 = Quat::Identity();  ///< joint frame on body 0: columns a, b, c in its principal frame
    Quat frame1 = Quat::Identity();
    double compliance = 0.0;  ///< attachment (prismatic: off-axis) compliance (m/N)
    double linearDamping = 0.0;   ///< Eq. 31 (1/s)
    double angularDamping = 0.0;  ///< Eq. 32 (1/s)
    bool collide = false;
    bool alive = false;
    uint32_t generation = 0;
    JointModel model;

    using Drive = JointDrive;
    JointType type() const { return static_cast<JointType>(model.index()); }
    /// The type's parameters; asking for another type than the joint's throws
    /// std::bad_variant_access.
    DistanceJoint& distance() { return std::get<DistanceJoint>(model); }
    const DistanceJoint& distance() const { return std::get<DistanceJoint>(model); }
    HingeJoint& hinge() { return std::get<HingeJoint>(model); }
    const HingeJoint& hinge() const { return std::get<HingeJoint>(model); }
    SphericalJoint& spherical() { return std::get<SphericalJoint>(model); }
    const SphericalJoint& spherical() const { return std::get<SphericalJoint>(model); }
    PrismaticJoint& prismatic() { return std::get<PrismaticJoint>(model); }
    const PrismaticJoint& prismatic() const { return std::get<PrismaticJoint>(model); }

    /// Zeroes every part's λ and impulse (paper 3.3.1: before each substep's solve).
    void resetMultipliers() {
        visitJointModel(model, [](auto& m) { std::apply([](auto&... part) { (part.reset(), ...); }, m.parts()); });
    }
    /// Sum of the positional (angular) correction impulses the parts gave body 0 in the current
    /// substep: force = |linearImpulse| / h² (Eq. 10), torque = |angularImpulse| / h² (Eq. 17).
    Vec3 linearImpulse() const { return summedImpulse<false>(); }
    Vec3 angularImpulse() const { return summedImpulse<true>(); }

private:
    template <bool Angular>
    Vec3 summedImpulse() const {
        Vec3 sum = Vec3::Zero();
        visitJointModel(model, [&](const auto& m) {
            std::apply([&](const auto&... part) { ((part.kAngular == Angular ? void(sum += part.impulse) : void()), ...); },
                       m.parts());
        });
        return sum;
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
