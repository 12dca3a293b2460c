#pragma once
/// The inspector: which body a click selects (the nearest the cursor's ray meets, by its
/// shape's bounding box in its own frame, as body_dragger.h grabs), and what the panel shows of
/// it, read from its components only (the engine layer): name, mass, pose, velocities and the
/// joints on it with their force, torque and error. The selected body is outlined in the view.

#include "view/body_dragger.h"

#include "ecs/registry.h"
#include "render/render_scene.h"

#include <optional>
#include <string>
#include <vector>

namespace substep::view {

/// The nearest body `ray` meets (static ones too) and where, in its own frame.
struct BodyHit {
    ecs::Entity entity;
    double distance = 0.0;  ///< along the ray (m)
    Vec3 local = Vec3::Zero();
};
std::optional<BodyHit> pickBody(ecs::Registry& registry, const Ray& ray);

/// A joint on the inspected body, as its readout gives it (DESIGN.md's CSV columns).
struct JointInspection {
    std::string name;  ///< its Name, or "joint N" by entity index
    double force = 0.0;   ///< N
    double torque = 0.0;  ///< N m
    double error = 0.0;   ///< m
};

/// What the inspector shows of a body.
struct BodyInspection {
    std::string name;     ///< its Name, or "body N" by entity index
    bool isStatic = false;
    double mass = 0.0;    ///< kg, as the world gave it (0 for a static body)
    Vec3 position = Vec3::Zero();
    Vec3 centreOfMass = Vec3::Zero();
    Vec3 velocity = Vec3::Zero();         ///< of the centre of mass (m/s)
    Vec3 angularVelocity = Vec3::Zero();  ///< rad/s, world axes
    std::vector<JointInspection> joints;  ///< every joint with the body on either side
    /// Filled by the session from the world's read-only view, which the components lack:
    Vec3 inertia = Vec3::Zero();  ///< principal moments (kg m²; 0 for a static body)
    int contacts = 0;             ///< contact points on the body in the last substep
};

/// The inspection of body `entity`; nullopt when it is no body any more (a restart, a load).
std::optional<BodyInspection> inspectBody(ecs::Registry& registry, ecs::Entity entity);

/// The twelve edges of `entity`'s shape's bounding box in its own frame, placed in the world,
/// in `colour` (the selection's outline); none when it is no body.
void outlineBody(ecs::Registry& registry, ecs::Entity entity, const render::Colour& colour,
                 std::vector<render::DebugLine>& lines);

}  // namespace substep::view
