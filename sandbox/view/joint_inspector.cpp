#include "view/joint_inspector.h"

#include "ecs/components.h"
#include "physics/joints/joint_geometry.h"

#include <algorithm>
#include <cmath>

namespace substep::view {

namespace {

std::string nameOf(ecs::Registry& registry, ecs::Entity entity, const char* kind) {
    if (entity.isNull()) return "the world";
    if (const ecs::Name* name = registry.tryGet<ecs::Name>(entity)) return name->value;
    return std::string(kind) + " " + std::to_string(entity.index);
}

/// The world's record of a joint component, or null while it has none.
const Joint* worldJoint(const World& world, const ecs::Joint& component) {
    return world.isValid(component.id) ? &world.joints()[component.id.index] : nullptr;
}

/// The angle (rad) between two unit vectors.
double angleBetween(const Vec3& a, const Vec3& b) {
    return std::atan2(a.cross(b).norm(), a.dot(b));
}

}  // namespace

std::optional<double> JointDetails::withinLimits() const {
    if (!limits || !(limits->upper > limits->lower)) return std::nullopt;
    return (coordinate - limits->lower) / (limits->upper - limits->lower);
}

std::optional<ecs::Entity> pickJoint(SceneInstance& scene, const Ray& ray, double radiansPerPixel,
                                     double pixels) {
    const World& world = scene.world();
    const std::span<const Body> bodies = world.bodies();
    std::optional<ecs::Entity> nearest;
    double best = pixels * radiansPerPixel;  // the angle off the ray an anchor may lie
    scene.registry.view<ecs::Joint>().each([&](ecs::Entity entity, const ecs::Joint& component) {
        const Joint* joint = worldJoint(world, component);
        if (joint == nullptr) return;
        const JointAnchors anchors = jointAnchors(*joint, bodies.data());
        for (const Vec3& anchor : {anchors.p0, anchors.p1}) {
            const Vec3 toAnchor = anchor - ray.origin;
            const double along = toAnchor.dot(ray.direction);
            if (!(along > 0.0)) continue;  // behind the camera
            const double off = std::atan2(toAnchor.cross(ray.direction).norm(), along);
            if (off < best) {
                best = off;
                nearest = entity;
            }
        }
    });
    return nearest;
}

std::optional<JointDetails> inspectJoint(SceneInstance& scene, ecs::Entity entity) {
    ecs::Registry& registry = scene.registry;
    const ecs::Joint* component = registry.tryGet<ecs::Joint>(entity);
    if (component == nullptr) return std::nullopt;
    const Joint* joint = worldJoint(scene.world(), *component);
    if (joint == nullptr) return std::nullopt;
    const Body* bodies = scene.world().bodies().data();
    JointDetails details;
    details.name = nameOf(registry, entity, "joint");
    details.type = jointTypeName(joint->type());
    details.body0 = nameOf(registry, component->body0, "body");
    details.body1 = nameOf(registry, component->body1, "body");
    details.force = component->readout.force;
    details.torque = component->readout.torque;
    details.error = component->readout.error;
    details.coordinate = component->readout.coordinate;
    const JointAnchors anchors = jointAnchors(*joint, bodies);
    details.anchor0 = anchors.p0;
    details.anchor1 = anchors.p1;
    // The frames' first columns are the joint axes (joint.h).
    const Quat frame0 = worldFrame0(*joint, bodies);
    const Quat frame1 = worldFrame1(*joint, bodies);
    const Vec3 axis0 = frame0 * Vec3::UnitX();
    const Vec3 axis1 = frame1 * Vec3::UnitX();
    const auto turn = [&] {
        const Quat relative = frame1 * frame0.conjugate();
        return 2.0 * std::atan2(relative.vec().norm(), std::abs(relative.w()));
    };
    switch (joint->type()) {
        case JointType::Distance:
            break;
        case JointType::Fixed:
            details.angleError = turn();
            break;
        case JointType::Hinge: {
            const HingeJoint& hinge = joint->hinge();
            details.angleError = angleBetween(axis0, axis1);
            details.hasCoordinate = true;
            if (hinge.hasLimits) details.limits = hinge.limits;
            details.hasDrive = hinge.drive != JointDrive::None;
            details.target = hinge.target;
            details.reach = wrapAngle(details.coordinate - hinge.target);
            break;
        }
        case JointType::Spherical: {
            const SphericalJoint& spherical = joint->spherical();
            details.hasCoordinate = true;
            if (spherical.hasSwingLimit) {
                details.limits = Range{0.0, spherical.swingLimit};
                details.angleError = std::max(details.coordinate - spherical.swingLimit, 0.0);
            }
            break;
        }
        case JointType::Prismatic: {
            const PrismaticJoint& prismatic = joint->prismatic();
            details.angleError = turn();
            details.hasCoordinate = true;
            details.angular = false;
            if (prismatic.hasLimits) details.limits = prismatic.limits;
            details.hasDrive = prismatic.drive != JointDrive::None;
            details.target = prismatic.target;
            details.reach = details.coordinate - prismatic.target;
            break;
        }
    }
    return details;
}

void highlightJoint(SceneInstance& scene, ecs::Entity entity, const render::Colour& colour,
                    std::vector<render::DebugLine>& lines) {
    const ecs::Joint* component = scene.registry.tryGet<ecs::Joint>(entity);
    if (component == nullptr) return;
    const Joint* joint = worldJoint(scene.world(), *component);
    if (joint == nullptr) return;
    const std::span<const Body> bodies = scene.world().bodies();
    const JointAnchors anchors = jointAnchors(*joint, bodies.data());
    // The cross's size follows the lever arms of the joint's moving bodies, so it shows on a coin
    // and on a crane alike.
    double lever = 0.0;
    if (bodies[joint->body0].invMass > 0.0) lever = std::max(lever, anchors.r0.norm());
    if (bodies[joint->body1].invMass > 0.0) lever = std::max(lever, anchors.r1.norm());
    const double arm = std::clamp(0.3 * lever, 0.005, 0.3);
    for (const Vec3& anchor : {anchors.p0, anchors.p1}) {
        for (int axis = 0; axis < 3; ++axis) {
            const Vec3 offset = arm * Vec3::Unit(axis);
            lines.push_back(
                {(anchor - offset).cast<float>(), (anchor + offset).cast<float>(), colour});
        }
    }
    if (joint->body0 != 0)
        lines.push_back({bodies[joint->body0].x.cast<float>(), anchors.p0.cast<float>(), colour});
    if (joint->body1 != 0)
        lines.push_back({bodies[joint->body1].x.cast<float>(), anchors.p1.cast<float>(), colour});
}

}  // namespace substep::view
