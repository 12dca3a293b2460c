#pragma once
/// Dragging a body with the mouse through a compliant spring (the paper's Fig. 5 interaction):
/// the spring joins a point of the body to a point of the world that follows the cursor across
/// a plane facing the camera. Going through the solver like any joint, the pull stays stable
/// however far or fast the cursor moves, and the body keeps its dynamics while held.
///
/// A static body that does not collide (a ceiling, a mount, a robot arm's target) is moved
/// directly instead: it follows the cursor across the same plane, and the joints attached to it
/// pull their bodies along. A static body that collides stays put: the broadphase files it in
/// its static tree once, so moving it would leave its collisions behind.
///
/// It works through the engine layer: the spring is a joint entity (a Joint component to the
/// world), moved by patching its anchor and removed by the physics system; a static body is
/// moved by patching its Transform. Bodies are found from their Transform and Collider.

#include "ecs/physics_system.h"
#include "render/render_scene.h"

#include <optional>

namespace substep::view {

/// A ray in world coordinates; direction of unit length.
struct Ray {
    Vec3 origin = Vec3::Zero();
    Vec3 direction = Vec3::UnitZ();
};

/// The ray through window point (x, y) (pixels, y down) of a `width` x `height` view of `camera`.
Ray cursorRay(const render::Camera& camera, float x, float y, float width, float height);

class BodyDragger {
  public:
    /// Grabs the nearest body the ray hits (its shape's local bounding box, exact for boxes): a
    /// dynamic one with a spring at the hit point, a static non-colliding one by that point.
    /// Returns false, doing nothing, when none is hit.
    bool grab(ecs::PhysicsSystem physics, const Ray& ray);
    /// Moves the spring's world end, or the held static body, to where the ray meets the drag
    /// plane.
    void drag(ecs::Registry& registry, const Ray& ray);
    /// Removes the spring, or lets the static body stay where it was put.
    void release(ecs::PhysicsSystem physics);
    /// Forgets what is held without touching a scene: for when the scene itself was replaced.
    void forget() {
        joint_.reset();
        staticBody_.reset();
    }
    bool active() const { return joint_.has_value() || staticBody_.has_value(); }
    /// The spring's joint entity, while a dynamic body is held.
    std::optional<ecs::Entity> joint() const { return joint_; }
    /// The static body's entity, while one is held.
    std::optional<ecs::Entity> staticBody() const { return staticBody_; }

    /// The spring as a line from the cursor's point to the body, when held.
    std::optional<render::DebugLine> line(const ecs::Registry& registry) const;

  private:
    std::optional<ecs::Entity> joint_;
    std::optional<ecs::Entity> staticBody_;
    Vec3 staticGrabOffset_ = Vec3::Zero();  ///< from the grab point to the static body's origin
    Vec3 planePoint_ = Vec3::Zero();   ///< the drag plane passes through the grab point...
    Vec3 planeNormal_ = Vec3::UnitZ();  ///< ...facing the ray it was grabbed along
};

}  // namespace substep::view
