#pragma once
/// A joint measured from components: its anchors and frames in the world, from the Transforms of
/// its two body entities and its definition, and the coordinates people read off a joint (a
/// hinge's angle, a slider's offset, a ball joint's swing and twist). Scene scripts and the
/// window's readouts use these, so they need nothing from the world itself.

#include "ecs/components.h"
#include "ecs/registry.h"

namespace substep::ecs {

/// A joint's attachment points and frames (columns a, b, c) in world coordinates.
struct JointPose {
    Vec3 anchor0 = Vec3::Zero();
    Vec3 anchor1 = Vec3::Zero();
    Quat frame0 = Quat::Identity();
    Quat frame1 = Quat::Identity();
    Vec3 axis0() const { return frame0 * Vec3::UnitX(); }
    Vec3 axis1() const { return frame1 * Vec3::UnitX(); }
};

/// The pose of `joint` on the current Transforms; a null (world) side, or one without a
/// Transform, is the world frame.
JointPose jointPose(const Registry& registry, const Joint& joint);

/// Angle of body 1 relative to body 0 about the hinge axis (rad, right-hand rule).
double hingeAngle(const JointPose& pose);
/// Offset of body 1's anchor from body 0's along the axis (m): a prismatic joint's coordinate.
double prismaticOffset(const JointPose& pose);
/// Angle between the two joint axes (rad): a spherical joint's swing.
double swingAngle(const JointPose& pose);
/// Twist about the mean axis between the normals projected off it (paper Eqs. 22-24), 0 where
/// that is undefined (axes opposite, a normal along the mean axis).
double twistAngle(const JointPose& pose);

}  // namespace substep::ecs
