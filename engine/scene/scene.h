#pragma once
/// A scene as data: world settings, named bodies and joints, and an optional camera. Scene files
/// (scene_loader.h) and the built-in scenes both produce one; buildScene turns it into entities
/// and, through the ECS physics system, a world.

#include "ecs/entity.h"
#include "ecs/physics_system.h"
#include "ecs/registry.h"
#include "physics/body.h"
#include "physics/joints/joint.h"
#include "physics/math.h"
#include "physics/soft/soft_body.h"
#include "physics/world.h"

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace substep {

struct SceneBody {
    std::string name;  ///< may be empty: unnamed bodies get no output columns
    BodyDef def;
    std::optional<Vec3> colour;  ///< linear RGB in [0, 1]; none: a palette colour by index
};

struct SceneJoint {
    std::string name;   ///< may be empty
    std::string body0;  ///< body name; empty or "world" means the world
    std::string body1;
    JointDef def;       ///< def.body0 / def.body1 are filled in by buildScene
};

/// A soft body (physics/soft/soft_body.h). def.attachments[i].body is ignored: buildScene
/// attaches to the body named attachBodies[i].
struct SceneSoftBody {
    std::string name;  ///< may be empty: unnamed soft bodies get no output columns
    SoftBodyDef def;
    std::vector<std::string> attachBodies;  ///< one body name per def.attachments entry
    std::optional<Vec3> colour;             ///< linear RGB in [0, 1]; none: the soft-body colour
};

struct SceneCamera {
    Vec3 position = Vec3(0.0, 1.5, 4.0);
    Vec3 target = Vec3(0.0, 0.5, 0.0);
    double fov = 0.8;  ///< vertical field of view (rad)
};

struct SceneDescription {
    std::string name;
    Vec3 gravity = Vec3(0.0, -9.81, 0.0);
    double dt = 1.0 / 60.0;
    int substeps = 20;
    int iterations = 1;
    bool sleeping = false;  ///< islands at rest stop being simulated (WorldSettings::sleeping)
    /// WorldSettings::jointProjection (the file's `joint_projection`).
    JointProjection jointProjection = WorldSettings{}.jointProjection;
    /// WorldSettings::sweptRestitution (the file's `restitution`: "swept" or "paper").
    bool sweptRestitution = WorldSettings{}.sweptRestitution;
    /// WorldSettings::softPatchFriction (the file's `soft_friction`: "patch" or "particle").
    bool softPatchFriction = WorldSettings{}.softPatchFriction;
    /// WorldSettings::softHeldContacts (the file's `soft_contacts`: "held" or "free").
    bool softHeldContacts = WorldSettings{}.softHeldContacts;
    std::vector<SceneBody> bodies;
    std::vector<SceneJoint> joints;
    std::vector<SceneSoftBody> softBodies;
    std::optional<SceneCamera> camera;
};

/// A scene built from a description: its entities and components, and the world the physics
/// system made from them and alone changes.
///
/// Returned by value and moved: nothing in it points at another member (the registry's pools
/// are on the heap, and the physics system binding registry and world is made on demand by
/// physics()), so a moved instance is whole.
class SceneInstance {
  public:
    /// One entity per body of the description (Transform, RigidBody, Collider, RenderMaterial,
    /// Name when named), one per joint (Joint, Name when named) and one per soft body
    /// (SoftBody, RenderMaterial, Name when named).
    ecs::Registry registry;
    std::vector<ecs::Entity> bodyEntities;      ///< in description order
    std::vector<ecs::Entity> jointEntities;     ///< in description order
    std::vector<ecs::Entity> softBodyEntities;  ///< in description order

    /// The entity whose Name is `name`, or the null entity when none is. Names are unique in a
    /// scene (the loader and buildScene check), bodies and joints alike in one namespace per kind:
    /// bodyNamed looks among bodies, jointNamed among joints.
    ecs::Entity bodyNamed(std::string_view name) const;
    ecs::Entity jointNamed(std::string_view name) const;
    ecs::Entity softBodyNamed(std::string_view name) const;
    /// The world id of the body or joint named `name` (null when there is none), for tests and
    /// diagnostics that read the world.
    BodyId bodyIdNamed(std::string_view name) const;
    JointId jointIdNamed(std::string_view name) const;
    /// The named bodies and joints with their world ids, in description order.
    std::vector<std::pair<std::string, BodyId>> namedBodyIds() const;
    std::vector<std::pair<std::string, JointId>> namedJointIds() const;

    /// The physics system over this instance's registry and world: the way to step the scene and
    /// change its world. Made per call and cheap; do not keep it across a move of the instance.
    ecs::PhysicsSystem physics() { return ecs::PhysicsSystem(registry, world_); }
    /// The world, read-only: global measures (energies, penetration) and tests. Changes go through
    /// components and physics().
    const World& world() const { return world_; }

  private:
    friend SceneInstance buildScene(const SceneDescription& description);
    explicit SceneInstance(World world) : world_(std::move(world)) {}

    World world_;
};

/// Builds the entities, then the world from them: bodies in description order, then joints in
/// description order (the world's storage order, on which every output depends), then soft
/// bodies. Body names referenced by joints and soft-body attachments must exist (the loader
/// checks files; built-in scenes are checked by their tests): an unknown name throws
/// std::invalid_argument.
SceneInstance buildScene(const SceneDescription& description);

}  // namespace substep
