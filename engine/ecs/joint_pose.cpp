/// Joints measured from the bodies' Transforms.

#include "ecs/joint_pose.h"

#include "physics/joints/joint_frame.h"

#include <cmath>

namespace substep::ecs {

namespace {

/// The user-frame pose of one side of a joint: the world for the null entity.
Transform sidePose(const Registry& registry, Entity side) {
    if (side.isNull()) return {};
    const Transform* transform = registry.tryGet<Transform>(side);
    return transform != nullptr ? *transform : Transform{};
}

}  // namespace

JointPose jointPose(const Registry& registry, const Joint& joint) {
    const Transform pose0 = sidePose(registry, joint.body0);
    const Transform pose1 = sidePose(registry, joint.body1);
    const JointDef& def = joint.def;
    return {.anchor0 = pose0.position + pose0.rotation * def.anchor0,
            .anchor1 = pose1.position + pose1.rotation * def.anchor1,
            .frame0 = (pose0.rotation * jointFrame(def.axis0, def.normal0)).normalized(),
            .frame1 = (pose1.rotation * jointFrame(def.axis1, def.normal1)).normalized()};
}

double hingeAngle(const JointPose& pose) {
    const Mat3 f0 = pose.frame0.toRotationMatrix();
    const Mat3 f1 = pose.frame1.toRotationMatrix();
    return signedAngle(f0.col(0), f0.col(1), f1.col(1));
}

double prismaticOffset(const JointPose& pose) { return (pose.anchor1 - pose.anchor0).dot(pose.axis0()); }

double swingAngle(const JointPose& pose) {
    const Vec3 a0 = pose.axis0();
    const Vec3 a1 = pose.axis1();
    return std::atan2(a0.cross(a1).norm(), a0.dot(a1));
}

double twistAngle(const JointPose& pose) {
    const Mat3 f0 = pose.frame0.toRotationMatrix();
    const Mat3 f1 = pose.frame1.toRotationMatrix();
    const Vec3 sum = f0.col(0) + f1.col(0);
    if (sum.norm() < 1e-6) return 0.0;
    const Vec3 n = sum.normalized();
    const Vec3 n0 = f0.col(1) - n.dot(f0.col(1)) * n;
    const Vec3 n1 = f1.col(1) - n.dot(f1.col(1)) * n;
    if (n0.norm() < 1e-9 || n1.norm() < 1e-9) return 0.0;
    return signedAngle(n, n0.normalized(), n1.normalized());
}

}  // namespace substep::ecs
