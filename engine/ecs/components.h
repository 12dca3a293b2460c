#pragma once
/// The components of the engine layer. A simulated body is an entity with Transform, RigidBody
/// and (usually) Collider; a joint is an entity of its own with a Joint naming two body entities;
/// Name and RenderMaterial are optional on either.
///
/// Components are the sandbox's whole view of the simulation. The physics system
/// (physics_system.h) is the one place that talks to the World: it creates a world object for
/// each new component, applies the components changed through Registry::patch (a body moved or
/// set moving, a friction, a joint's compliance, limit or drive) before each step, and after each
/// step writes back what the simulation made of them: Transform, the velocities and centre of
/// mass in RigidBody, the readouts in Joint.
///
/// Collider is kept apart from RigidBody because it answers a different question (what the body
/// touches, not how it moves): a body without a Collider is a massed point or frame that
/// collides with nothing (it needs RigidBody::mass), and the renderer reads shapes from
/// Collider alone.

#include "ecs/entity.h"
#include "physics/body.h"
#include "physics/collision/shape.h"
#include "physics/handles.h"
#include "physics/joints/joint.h"
#include "physics/math.h"

#include <memory>
#include <string>

namespace substep::ecs {

/// A human-readable name (scene files' `name`); unnamed entities have no Name.
struct Name {
    std::string value;
};

/// The entity's user frame in world coordinates: the frame scenes give poses and joint anchors
/// in and the renderer draws shapes in. For a simulated body the PhysicsSystem writes it after
/// every step; before the body exists it is the pose the body is created at. Patched, it moves
/// the body there (a static mount carried by hand, a body placed by a script). A static body that
/// collides is filed once in the broadphase's static tree: move only those that do not collide.
struct Transform {
    Vec3 position = Vec3::Zero();
    Quat rotation = Quat::Identity();
};

/// How a body moves: what BodyDef needs besides the pose (Transform) and the shape (Collider),
/// the world's id once the PhysicsSystem has created the body, and the motion it writes back.
struct RigidBody {
    BodyType type = BodyType::Dynamic;
    double mass = 0.0;                    ///< > 0 overrides the collider's density
    double density = 1000.0;              ///< kg/m³, used when mass is 0
    /// Velocity of the centre of mass: the initial one, then the simulated one after every
    /// step. Patched, it sets the body moving (a striker launched by a script).
    Vec3 velocity = Vec3::Zero();
    Vec3 angularVelocity = Vec3::Zero();  ///< like velocity (rad/s, world axes)
    BodyId id;                            ///< null until PhysicsSystem::sync() creates the body

    // Written by the PhysicsSystem when it creates the body and after every step.
    Vec3 centreOfMass = Vec3::Zero();  ///< world position of the centre of mass
    double simulatedMass = 0.0;        ///< the mass the world gave it (0 for a static body)
};

/// What a body touches: its shape (in the user frame) and surface properties.
struct Collider {
    Shape shape;
    double staticFriction = 0.5;
    double dynamicFriction = 0.3;
    double restitution = 0.0;
    bool collide = true;  ///< false: the shape gives mass and a look but meets nothing
    uint32_t collisionGroup = 1;   ///< collision filter (BodyDef::collisionGroup), fixed at creation
    uint32_t collisionMask = ~0u;  ///< BodyDef::collisionMask
};

/// A joint between two body entities; a null entity is the world (anchor and axes then in world
/// coordinates). def.body0 and def.body1 are ignored: the PhysicsSystem fills them from the
/// entities' bodies. Patched, the world joint takes the new definition's parameters (anchors,
/// frames, compliances, limits, drives, damping) and keeps its running state (a motor's angle).
struct Joint {
    JointDef def;
    Entity body0;
    Entity body1;
    JointId id;  ///< null until PhysicsSystem::sync() creates the joint

    // Written by the PhysicsSystem after every step.
    JointReadout readout;  ///< force, torque, error and stored energy (DESIGN.md's CSV columns)
    /// The joint's coordinate: a hinge's angle (rad), a prismatic joint's offset along its axis
    /// (m); 0 for the other types.
    double coordinate = 0.0;
    double target = 0.0;  ///< the drive's current target (a motor advances it each substep)
};

/// How the renderer draws an entity: a colour, and a mesh that overrides the one derived from
/// the collider's shape (for a look finer than the collision geometry).
struct RenderMaterial {
    Vec3 colour = Vec3(0.7, 0.7, 0.7);  ///< linear RGB in [0, 1]
    bool visible = true;
    std::shared_ptr<const TriangleMesh> mesh;  ///< optional, in the user frame; null: from Collider
};

}  // namespace substep::ecs
