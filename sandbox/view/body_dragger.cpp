#include "view/body_dragger.h"

#include "ecs/components.h"
#include "ecs/joint_pose.h"
#include "physics/collision/shape_bounds.h"

#include <cmath>
#include <limits>

namespace substep::view {

namespace {

/// Spring stiffness per kilogram held (N/m per kg): a body sags by g/200, 5 cm under 10 m/s²,
/// so it follows the cursor closely yet visibly hangs from a spring. Compliance is its inverse.
constexpr double kStiffnessPerKilogram = 200.0;
/// Damping of the held point's velocity (1/s), so the body settles under the cursor instead of
/// swinging on the spring for ever.
constexpr double kDamping = 2.0;

/// Where the ray enters the box [min, max] (slab test), as a distance along it; none if missed.
std::optional<double> rayBoxEntry(const Vec3& origin, const Vec3& direction, const Vec3& min, const Vec3& max) {
    double enter = 0.0;
    double leave = std::numeric_limits<double>::infinity();
    for (int axis = 0; axis < 3; ++axis) {
        if (std::abs(direction[axis]) < 1e-12) {
            if (origin[axis] < min[axis] || origin[axis] > max[axis]) return std::nullopt;
            continue;
        }
        double near = (min[axis] - origin[axis]) / direction[axis];
        double far = (max[axis] - origin[axis]) / direction[axis];
        if (near > far) std::swap(near, far);
        enter = std::max(enter, near);
        leave = std::min(leave, far);
        if (enter > leave) return std::nullopt;
    }
    return enter;
}

/// A body the cursor moves directly rather than through a spring: static (it has no mass to pull)
/// and out of the collision pipeline (a colliding static body sits in the broadphase's static
/// tree, which is not updated when it moves).
bool movesDirectly(const ecs::RigidBody& body, const ecs::Collider& collider) {
    return body.type == BodyType::Static && !collider.collide && collider.shape.type != ShapeType::None;
}

}  // namespace

Ray cursorRay(const render::Camera& camera, float x, float y, float width, float height) {
    const Vec3 position = camera.position.cast<double>();
    const Vec3 forward = (camera.target - camera.position).cast<double>().normalized();
    const Vec3 right = forward.cross(camera.up.cast<double>()).normalized();
    const Vec3 up = right.cross(forward);
    const double halfHeight = std::tan(0.5 * camera.fovY);
    const double halfWidth = halfHeight * width / std::max(height, 1.0f);
    const double ndcX = 2.0 * x / std::max(width, 1.0f) - 1.0;
    const double ndcY = 1.0 - 2.0 * y / std::max(height, 1.0f);
    return {position, (forward + ndcX * halfWidth * right + ndcY * halfHeight * up).normalized()};
}

bool BodyDragger::grab(ecs::PhysicsSystem physics, const Ray& ray) {
    if (active()) release(physics);
    ecs::Registry& registry = physics.registry();
    std::optional<ecs::Entity> hitBody;
    Vec3 hitLocal = Vec3::Zero();
    double nearest = std::numeric_limits<double>::infinity();
    registry.view<ecs::RigidBody, ecs::Transform, ecs::Collider>().each(
        [&](ecs::Entity entity, const ecs::RigidBody& body, const ecs::Transform& transform,
            const ecs::Collider& collider) {
            if (body.id.isNull()) return;
            if (!(body.simulatedMass > 0.0 || movesDirectly(body, collider))) return;
            // The ray in the body's own frame (the frame its shape is given in), tested against
            // the shape's bounds there.
            const Vec3 origin = transform.rotation.conjugate() * (ray.origin - transform.position);
            const Vec3 direction = transform.rotation.conjugate() * ray.direction;
            const Aabb bounds = shapeLocalBounds(collider.shape);
            const std::optional<double> distance = rayBoxEntry(origin, direction, bounds.min, bounds.max);
            if (distance && *distance < nearest) {
                nearest = *distance;
                hitLocal = origin + *distance * direction;
                hitBody = entity;
            }
        });
    if (!hitBody) return false;

    planePoint_ = ray.origin + nearest * ray.direction;
    planeNormal_ = ray.direction;
    const ecs::RigidBody& body = registry.get<ecs::RigidBody>(*hitBody);
    if (!(body.simulatedMass > 0.0)) {
        staticBody_ = *hitBody;
        staticGrabOffset_ = registry.get<ecs::Transform>(*hitBody).position - planePoint_;
        return true;
    }
    JointDef def;
    def.type = JointType::Distance;
    def.anchor0 = planePoint_;
    def.anchor1 = hitLocal;
    def.compliance = 1.0 / (kStiffnessPerKilogram * body.simulatedMass);
    def.linearDamping = kDamping;
    // A joint entity to the world (body0 null); the physics system makes it at the next step.
    const ecs::Entity spring = registry.create();
    registry.emplace<ecs::Joint>(spring, ecs::Joint{.def = def, .body0 = ecs::kNullEntity, .body1 = *hitBody});
    joint_ = spring;
    return true;
}

void BodyDragger::drag(ecs::Registry& registry, const Ray& ray) {
    if (!active()) return;
    const double facing = ray.direction.dot(planeNormal_);
    if (std::abs(facing) < 1e-6) return;  // the ray runs along the plane: keep the last point
    const double distance = (planePoint_ - ray.origin).dot(planeNormal_) / facing;
    if (distance <= 0.0) return;  // the plane is behind the camera
    const Vec3 cursor = ray.origin + distance * ray.direction;
    if (joint_ && registry.has<ecs::Joint>(*joint_)) {
        // The world's anchor is a world point (the world body's frame is the world's).
        registry.patch<ecs::Joint>(*joint_, [&](ecs::Joint& joint) { joint.def.anchor0 = cursor; });
    } else if (staticBody_ && registry.has<ecs::Transform>(*staticBody_)) {
        // Moved, not pushed: the physics system carries it there at rest, and only the joints
        // attached to it feel the move (they pull their bodies along).
        registry.patch<ecs::Transform>(*staticBody_, [&](ecs::Transform& transform) {
            transform.position = cursor + staticGrabOffset_;
        });
    }
}

void BodyDragger::release(ecs::PhysicsSystem physics) {
    if (joint_) physics.destroy(*joint_);
    forget();
}

std::optional<render::DebugLine> BodyDragger::line(const ecs::Registry& registry) const {
    if (!joint_) return std::nullopt;
    const ecs::Joint* joint = registry.tryGet<ecs::Joint>(*joint_);
    if (joint == nullptr) return std::nullopt;
    const ecs::JointPose pose = ecs::jointPose(registry, *joint);
    render::DebugLine line;
    line.from = pose.anchor0.cast<float>();
    line.to = pose.anchor1.cast<float>();
    line.colour = render::Colour(1.0f, 0.85f, 0.2f);
    return line;
}

}  // namespace substep::view
