#pragma once
/// The components of the engine layer. A simulated body is an entity with Transform, RigidBody
/// and (usually) Collider; a joint is an entity of its own with a Joint naming two body entities;
/// Name and RenderMaterial are optional on either. Soft bodies get their component with the
/// soft-body issue; they are not here yet.
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
/// every step; before the body exists it is the pose the body is created at.
struct Transform {
    Vec3 position = Vec3::Zero();
    Quat rotation = Quat::Identity();
};

/// How a body moves: what BodyDef needs besides the pose (Transform) and the shape (Collider),
/// and the world's id once the PhysicsSystem has created the body.
struct RigidBody {
    BodyType type = BodyType::Dynamic;
    double mass = 0.0;                    ///< > 0 overrides the collider's density
    double density = 1000.0;              ///< kg/m³, used when mass is 0
    Vec3 velocity = Vec3::Zero();         ///< initial, of the centre of mass
    Vec3 angularVelocity = Vec3::Zero();  ///< initial
    BodyId id;                            ///< null until PhysicsSystem::sync() creates the body
};

/// What a body touches: its shape (in the user frame) and surface properties.
struct Collider {
    Shape shape;
    double staticFriction = 0.5;
    double dynamicFriction = 0.3;
    double restitution = 0.0;
    bool collide = true;  ///< false: the shape gives mass and a look but meets nothing
};

/// A joint between two body entities; a null entity is the world (anchor and axes then in world
/// coordinates). def.body0 and def.body1 are ignored: the PhysicsSystem fills them from the
/// entities' bodies.
struct Joint {
    JointDef def;
    Entity body0;
    Entity body1;
    JointId id;  ///< null until PhysicsSystem::sync() creates the joint
};

/// How the renderer draws an entity: a colour, and a mesh that overrides the one derived from
/// the collider's shape (for a look finer than the collision geometry).
struct RenderMaterial {
    Vec3 colour = Vec3(0.7, 0.7, 0.7);  ///< linear RGB in [0, 1]
    bool visible = true;
    std::shared_ptr<const TriangleMesh> mesh;  ///< optional, in the user frame; null: from Collider
};

}  // namespace substep::ecs
