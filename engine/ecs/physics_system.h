#pragma once
/// The physics system: builds the XPBD world from components and writes the simulation back.
///
/// It holds no state of its own, only references to a registry and a world, so it is cheap to
/// make wherever it is needed (SceneInstance::physics() makes one on demand). That keeps a
/// registry and a world that live side by side in a movable object (SceneInstance) free of
/// pointers that a move would leave dangling. The physics core never sees the ECS: the system
/// turns components into BodyDef/JointDef and keeps the returned ids in the components.
///
/// Entities with physics components must be destroyed through destroy(), not Registry::destroy,
/// so their world bodies and joints go with them. (An automatic cleanup pass would need the
/// system to remember which world objects it made, i.e. state that must follow moves; one
/// explicit call is simpler and does its work at once.)

#include "ecs/entity.h"
#include "ecs/registry.h"
#include "physics/world.h"

namespace substep::ecs {

class PhysicsSystem {
  public:
    /// Binds the system to a registry and a world; both must outlive it.
    PhysicsSystem(Registry& registry, World& world) : registry_(&registry), world_(&world) {}

    /// Creates the world objects that components ask for and do not have yet. First bodies, for
    /// every entity with RigidBody and Transform (Collider optional) whose RigidBody::id is null,
    /// in the RigidBody pool's dense order (the order the components were added, as long as none
    /// was removed); then joints, for every Joint with a null id whose body entities are the
    /// world (null) or have their bodies, in the Joint pool's dense order. A Joint whose body
    /// entity has been destroyed stays dormant.
    void sync();

    /// sync(), then one world step of dt, then writeTransforms().
    void step(double dt);

    /// Sets each simulated body's Transform to the pose of its user frame (for a caller that
    /// steps the world itself). Static bodies keep the Transform they were created from.
    void writeTransforms();

    /// Destroys the entity, its world body (with every world joint attached to that body), the
    /// world joint of its Joint component, and the world joints of Joint components that name
    /// it; those components stay, with a null id, and sync() leaves them dormant. Invalid
    /// entities are ignored.
    void destroy(Entity entity);

    Registry& registry() const { return *registry_; }
    World& world() const { return *world_; }

  private:
    Registry* registry_;
    World* world_;
};

}  // namespace substep::ecs
