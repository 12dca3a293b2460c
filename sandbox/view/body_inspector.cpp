#include "view/body_inspector.h"

#include "ecs/components.h"
#include "physics/collision/shape_bounds.h"

#include <array>
#include <limits>

namespace substep::view {

namespace {

/// The distance along (origin, direction) at which the ray enters the box [lower, upper], or
/// nullopt when it misses it or the box lies behind; 0 from inside.
std::optional<double> rayEntry(const Vec3& origin, const Vec3& direction, const Vec3& lower, const Vec3& upper) {
    double near = 0.0;
    double far = std::numeric_limits<double>::infinity();
    for (int axis = 0; axis < 3; ++axis) {
        if (std::abs(direction[axis]) < 1e-12) {
            if (origin[axis] < lower[axis] || origin[axis] > upper[axis]) return std::nullopt;
            continue;
        }
        double t0 = (lower[axis] - origin[axis]) / direction[axis];
        double t1 = (upper[axis] - origin[axis]) / direction[axis];
        if (t0 > t1) std::swap(t0, t1);
        near = std::max(near, t0);
        far = std::min(far, t1);
        if (near > far) return std::nullopt;
    }
    return near;
}

std::string nameOf(ecs::Registry& registry, ecs::Entity entity, const char* kind) {
    if (const ecs::Name* name = registry.tryGet<ecs::Name>(entity)) return name->value;
    return std::string(kind) + " " + std::to_string(entity.index);
}

}  // namespace

std::optional<BodyHit> pickBody(ecs::Registry& registry, const Ray& ray) {
    std::optional<BodyHit> hit;
    registry.view<ecs::RigidBody, ecs::Transform, ecs::Collider>().each(
        [&](ecs::Entity entity, const ecs::RigidBody& body, const ecs::Transform& transform,
            const ecs::Collider& collider) {
            if (body.id.isNull()) return;
            // Planes and other unbounded shapes have no box to click.
            const Aabb bounds = shapeLocalBounds(collider.shape);
            if (!bounds.min.allFinite() || !bounds.max.allFinite()) return;
            const Vec3 origin = transform.rotation.conjugate() * (ray.origin - transform.position);
            const Vec3 direction = transform.rotation.conjugate() * ray.direction;
            const std::optional<double> distance = rayEntry(origin, direction, bounds.min, bounds.max);
            if (distance && (!hit || *distance < hit->distance)) {
                hit = BodyHit{entity, *distance, origin + *distance * direction};
            }
        });
    return hit;
}

std::optional<BodyInspection> inspectBody(ecs::Registry& registry, ecs::Entity entity) {
    const ecs::RigidBody* body = registry.tryGet<ecs::RigidBody>(entity);
    const ecs::Transform* transform = registry.tryGet<ecs::Transform>(entity);
    if (body == nullptr || transform == nullptr) return std::nullopt;
    BodyInspection inspection;
    inspection.name = nameOf(registry, entity, "body");
    inspection.isStatic = !(body->simulatedMass > 0.0);
    inspection.mass = body->simulatedMass;
    inspection.position = transform->position;
    inspection.centreOfMass = body->centreOfMass;
    inspection.velocity = body->velocity;
    inspection.angularVelocity = body->angularVelocity;
    registry.view<ecs::Joint>().each([&](ecs::Entity jointEntity, const ecs::Joint& joint) {
        if (joint.body0 != entity && joint.body1 != entity) return;
        inspection.joints.push_back({nameOf(registry, jointEntity, "joint"), joint.readout.force, joint.readout.torque,
                                     joint.readout.error});
    });
    return inspection;
}

void outlineBody(ecs::Registry& registry, ecs::Entity entity, const render::Colour& colour,
                 std::vector<render::DebugLine>& lines) {
    const ecs::Transform* transform = registry.tryGet<ecs::Transform>(entity);
    const ecs::Collider* collider = registry.tryGet<ecs::Collider>(entity);
    if (transform == nullptr || collider == nullptr) return;
    const Aabb bounds = shapeLocalBounds(collider->shape);
    if (!bounds.min.allFinite() || !bounds.max.allFinite()) return;
    std::array<render::Vec3f, 8> corners;
    for (int i = 0; i < 8; ++i) {
        const Vec3 local((i & 1) ? bounds.max.x() : bounds.min.x(), (i & 2) ? bounds.max.y() : bounds.min.y(),
                         (i & 4) ? bounds.max.z() : bounds.min.z());
        corners[static_cast<std::size_t>(i)] = (transform->position + transform->rotation * local).cast<float>();
    }
    // Edges join corners that differ in one bit.
    for (int i = 0; i < 8; ++i) {
        for (const int bit : {1, 2, 4}) {
            if ((i & bit) == 0) {
                lines.push_back({corners[static_cast<std::size_t>(i)], corners[static_cast<std::size_t>(i | bit)], colour});
            }
        }
    }
}

}  // namespace substep::view
