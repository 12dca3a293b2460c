#pragma once
/// The physics system: the one place where the engine layer meets the XPBD world.
///
/// It creates a world object for every new component (RigidBody with Transform, Joint),
/// applies the components changed through Registry::patch before each step, steps the world,
/// writes back what the simulation made of them (Transform; RigidBody's velocities and centre of
/// mass; Joint's readout), and destroys the world objects of destroyed entities. The sandbox
/// (commands, window, scene scripts, drawing, dragging) goes through it and the components; it
/// never changes the World itself.
///
/// It holds no state of its own, only references to a registry and a world, so it is cheap to
/// make wherever it is needed (SceneInstance::physics() makes one on demand). That keeps a
/// registry and a world that live side by side in a movable object (SceneInstance) free of
/// pointers that a move would leave dangling. The physics core never sees the ECS: the system
/// turns components into BodyDef/JointDef and keeps the returned ids in the components.
///
/// Entities with physics components must be destroyed through destroy(), not Registry::destroy,
/// so their world bodies and joints go with them.

#include "ecs/entity.h"
#include "ecs/registry.h"
#include "ecs/soft_body_component.h"
#include "physics/debug_draw.h"
#include "physics/world.h"

#include <chrono>
#include <span>
#include <vector>

namespace substep::ecs {

class PhysicsSystem {
  public:
    /// Binds the system to a registry and a world; both must outlive it.
    PhysicsSystem(Registry& registry, World& world) : registry_(&registry), world_(&world) {}

    /// Brings the world up to date with the components:
    /// - creates bodies for RigidBody + Transform entities (Collider optional) whose id is null,
    ///   in the RigidBody pool's dense order (the order the components were added, as long as
    ///   none was removed), filling RigidBody::centreOfMass and simulatedMass; then joints, for
    ///   every Joint with a null id whose body entities are the world (null) or have their
    ///   bodies, in the Joint pool's dense order. A Joint whose body entity has been destroyed
    ///   stays dormant;
    /// - applies the patched components, in the order they were patched: Transform moves the
    ///   body, RigidBody sets its velocities, Collider its friction, restitution and collide flag,
    ///   Joint the joint's parameters (World::updateJoint). A Collider's shape and a RigidBody's
    ///   type and mass are fixed at creation, and so is a whole SoftBody (its patches are dropped):
    ///   to change them, destroy the entity and make another.
    void sync();

    /// sync(), one world step of dt, writeBack(). Returns the time of the world's step alone
    /// (what `bench`, `run` and `sweep` report), without the system's own work.
    std::chrono::steady_clock::duration step(double dt);
    /// step() a substep at a time (World::beginFrame): beginFrame syncs and starts a frame of dt;
    /// substep() solves the next substep and writes the state back (false when none is left);
    /// finishFrame() solves the rest, ends the frame and writes back, returning the time of the
    /// world's work it did. The three give step()'s bytes.
    void beginFrame(double dt);
    bool substep();
    std::chrono::steady_clock::duration finishFrame();
    /// Whether a frame begun with beginFrame is still open; its substeps done and in all.
    bool frameOpen() const { return world_->frameOpen(); }
    int frameSubstepsDone() const { return world_->frameSubstepsDone(); }
    int frameSubsteps() const { return world_->frameSubsteps(); }
    /// Records what each constraint moved in every substep (World::recordCorrections; read
    /// through world().corrections()), or stops: off, the solve pays nothing for it.
    void recordCorrections(bool on) { world_->recordCorrections(on); }

    /// Writes the world's state into the components: each body's Transform (the pose of its user
    /// frame), velocities and centre of mass, each joint's readout and each soft body's readout. buildScene calls it once
    /// after creating a scene, so components read the initial state as the world has it.
    void writeBack();

    /// The world's state now (physics/world_snapshot.h), for rewinding.
    WorldSnapshot snapshot() const;
    /// Puts the world back in `snapshot`'s state and writes it back into the components. The
    /// entities must be those the snapshot was taken with (no body or joint created or
    /// destroyed since); settings stay the current ones.
    void restore(const WorldSnapshot& snapshot);

    /// Destroys the entity, its world body (with every world joint attached to that body), the
    /// world joint of its Joint component, its world soft body, and the world joints of Joint
    /// components that name it; those components stay, with a null id, and sync() leaves them
    /// dormant. Soft bodies attached to the entity stay and lose that attachment (the world's
    /// rule). Invalid entities are ignored.
    void destroy(Entity entity);

    /// The solver settings (substeps, iterations, gravity, velocity pass, ...).
    const WorldSettings& settings() const { return world_->settings(); }
    void setSettings(const WorldSettings& settings) { world_->setSettings(settings); }
    /// Asks the next step to repair large joint violations first (after a script or a knob has
    /// moved limits or targets far from the current pose; WorldSettings::repairDistance).
    void requestRepair() { world_->requestRepair(); }

    /// The physics core's debug draw list of the current state (physics/debug_draw.h).
    void debugDraw(const DebugDrawOptions& options, DebugDrawList& list) const {
        drawWorld(*world_, options, list);
    }

    /// A soft body's current particle positions, for drawing its surface (empty while the
    /// component has no live soft body).
    std::span<const Vec3> softBodyPositions(const SoftBody& softBody) const {
        return world_->softBodyPositions(softBody.id);
    }
    /// A soft body's current surface: positions and the boundary quads of its lattice, also split
    /// into triangles wound counter-clockwise seen from outside (empty while it has none).
    SoftSurface softBodySurface(const SoftBody& softBody) const {
        return world_->softBodySurface(softBody.id);
    }

    Registry& registry() const { return *registry_; }
    /// Read-only: global measures (energies, penetration, step times) for the sandbox's readouts.
    const World& world() const { return *world_; }

  private:
    void createNewObjects();
    void applyChanges();

    Registry* registry_;
    World* world_;
};

/// A soft body's whole readout now, its volume (the elements' summed current volume) included:
/// the component's readout leaves the volume out after a step (a pass over every element, 3 %
/// of `substep run rc_car`'s CPU time, that only a CSV column, a capture or a test reads).
/// Zeros while the component has no live soft body, as writeBack writes them.
SoftBodyReadout softBodyReadout(const World& world, const SoftBody& softBody);

}  // namespace substep::ecs
