#include "view/body_dragger.h"

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
/// tree, which is not updated when it moves). The world's own anchor body has no shape.
bool movesDirectly(const Body& body) {
    return !body.isDynamic() && !body.collide && body.shape.type != ShapeType::None;
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

bool BodyDragger::grab(World& world, const Ray& ray) {
    if (active()) release(world);
    std::optional<BodyId> hitBody;
    Vec3 hitLocal = Vec3::Zero();
    double nearest = std::numeric_limits<double>::infinity();
    const std::span<const Body> bodies = world.bodies();
    for (std::size_t index = 0; index < bodies.size(); ++index) {
        const Body& body = bodies[index];
        if (!body.alive || !(body.isDynamic() || movesDirectly(body))) continue;
        // The ray in the body's own frame (the frame its shape is given in), tested against the
        // shape's bounds there.
        const Quat userToWorld = body.q * body.userRotation;
        const Vec3 userOrigin = body.pointToWorld(body.userOrigin);
        const Vec3 origin = userToWorld.conjugate() * (ray.origin - userOrigin);
        const Vec3 direction = userToWorld.conjugate() * ray.direction;
        const Aabb bounds = shapeLocalBounds(body.shape);
        const std::optional<double> distance = rayBoxEntry(origin, direction, bounds.min, bounds.max);
        if (distance && *distance < nearest) {
            nearest = *distance;
            hitLocal = origin + *distance * direction;
            hitBody = BodyId{static_cast<uint32_t>(index), body.generation};
        }
    }
    if (!hitBody) return false;

    planePoint_ = ray.origin + nearest * ray.direction;
    planeNormal_ = ray.direction;
    const Body& body = world.body(*hitBody);
    if (!body.isDynamic()) {
        staticBody_ = *hitBody;
        staticGrabOffset_ = body.x - planePoint_;
        return true;
    }
    JointDef def;
    def.type = JointType::Distance;
    def.body1 = *hitBody;
    def.anchor0 = planePoint_;
    def.anchor1 = hitLocal;
    def.compliance = 1.0 / (kStiffnessPerKilogram * body.mass);
    def.linearDamping = kDamping;
    joint_ = world.createJoint(def);
    return true;
}

void BodyDragger::drag(World& world, const Ray& ray) {
    if (!active()) return;
    const double facing = ray.direction.dot(planeNormal_);
    if (std::abs(facing) < 1e-6) return;  // the ray runs along the plane: keep the last point
    const double distance = (planePoint_ - ray.origin).dot(planeNormal_) / facing;
    if (distance <= 0.0) return;  // the plane is behind the camera
    const Vec3 cursor = ray.origin + distance * ray.direction;
    if (joint_ && world.isValid(*joint_)) {
        // The world's anchor is a world point (the world body's frame is the world's).
        world.joint(*joint_).anchor0 = cursor;
    } else if (staticBody_ && world.isValid(*staticBody_)) {
        // Moved, not pushed: the previous pose goes along, so the body is still at rest where it
        // is put, and only the joints attached to it feel the move (they pull their bodies along).
        Body& body = world.body(*staticBody_);
        body.x = cursor + staticGrabOffset_;
        body.xPrev = body.x;
    }
}

void BodyDragger::release(World& world) {
    if (joint_ && world.isValid(*joint_)) world.destroyJoint(*joint_);
    forget();
}

std::optional<render::DebugLine> BodyDragger::line(const World& world) const {
    if (!joint_ || !world.isValid(*joint_)) return std::nullopt;
    const Joint& joint = world.joint(*joint_);
    const Body& body = world.bodies()[joint.body1];
    render::DebugLine line;
    line.from = joint.anchor0.cast<float>();
    line.to = body.pointToWorld(joint.anchor1).cast<float>();
    line.colour = render::Colour(1.0f, 0.85f, 0.2f);
    return line;
}

}  // namespace substep::view
