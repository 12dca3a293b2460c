#pragma once
/// The conversion between a physics BodyDef and the components that describe a body
/// (Transform, RigidBody, Collider): the one place that knows which BodyDef field lives in which
/// component. A field added to BodyDef must be added here, or it is lost on the way through.

#include "ecs/components.h"
#include "ecs/entity.h"
#include "physics/body.h"

namespace substep::ecs {

class Registry;

/// A BodyDef split into components; RigidBody::id is null.
struct BodyComponents {
    Transform transform;
    RigidBody rigidBody;
    Collider collider;
};

/// Splits a definition into components, field for field.
BodyComponents toBodyComponents(const BodyDef& def);

/// The definition the components describe; without a collider the shape is none and the body
/// collides with nothing.
BodyDef toBodyDef(const Transform& transform, const RigidBody& rigidBody, const Collider* collider);

/// Gives an entity the Transform, RigidBody and Collider of a definition (the body itself is
/// created by PhysicsSystem::sync()).
void emplaceBody(Registry& registry, Entity entity, const BodyDef& def);

}  // namespace substep::ecs
