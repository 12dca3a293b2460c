/// BodyDef <-> Transform, RigidBody, Collider.

#include "ecs/body_components.h"

#include "ecs/registry.h"

namespace substep::ecs {

BodyComponents toBodyComponents(const BodyDef& def) {
    return {
        .transform = {.position = def.position, .rotation = def.orientation},
        .rigidBody = {.type = def.type,
                      .mass = def.mass,
                      .density = def.density,
                      .velocity = def.velocity,
                      .angularVelocity = def.angularVelocity,
                      .id = {}},
        .collider = {.shape = def.shape,
                     .staticFriction = def.staticFriction,
                     .dynamicFriction = def.dynamicFriction,
                     .restitution = def.restitution,
                     .collide = def.collide,
                     .collisionGroup = def.collisionGroup,
                     .collisionMask = def.collisionMask},
    };
}

BodyDef toBodyDef(const Transform& transform, const RigidBody& rigidBody,
                  const Collider* collider) {
    BodyDef def{
        .type = rigidBody.type,
        .mass = rigidBody.mass,
        .density = rigidBody.density,
        .position = transform.position,
        .orientation = transform.rotation,
        .velocity = rigidBody.velocity,
        .angularVelocity = rigidBody.angularVelocity,
    };
    if (collider != nullptr) {
        def.shape = collider->shape;
        def.staticFriction = collider->staticFriction;
        def.dynamicFriction = collider->dynamicFriction;
        def.restitution = collider->restitution;
        def.collide = collider->collide;
        def.collisionGroup = collider->collisionGroup;
        def.collisionMask = collider->collisionMask;
    } else {
        def.collide = false;
    }
    return def;
}

void emplaceBody(Registry& registry, Entity entity, const BodyDef& def) {
    BodyComponents components = toBodyComponents(def);
    registry.emplace<Transform>(entity, std::move(components.transform));
    registry.emplace<RigidBody>(entity, std::move(components.rigidBody));
    registry.emplace<Collider>(entity, std::move(components.collider));
}

}  // namespace substep::ecs
