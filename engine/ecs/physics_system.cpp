/// PhysicsSystem: components -> world objects, world state -> Transform.

#include "ecs/physics_system.h"

#include "ecs/body_components.h"
#include "ecs/components.h"

#include <cstddef>
#include <optional>
#include <span>

namespace substep::ecs {

namespace {

/// The world body a joint side refers to: the world for the null entity, nothing while the
/// entity has no body (not created yet, or destroyed).
std::optional<BodyId> jointSideBody(const Registry& registry, Entity side) {
    if (side.isNull()) return BodyId{};
    const RigidBody* rigidBody = registry.tryGet<RigidBody>(side);
    if (rigidBody == nullptr || rigidBody->id.isNull()) return std::nullopt;
    return rigidBody->id;
}

}  // namespace

void PhysicsSystem::sync() {
    Registry& registry = *registry_;
    World& world = *world_;

    // Bodies before joints, each in dense (creation) order, so a scene reaches the world in the
    // order it was described: the world's storage order, and with it every output, depends on it.
    if (ComponentPool<RigidBody>* rigidBodies = registry.findPool<RigidBody>()) {
        const std::span<const Entity> entities = rigidBodies->entities();
        const std::span<RigidBody> components = rigidBodies->components();
        for (std::size_t i = 0; i < components.size(); ++i) {
            RigidBody& rigidBody = components[i];
            if (!rigidBody.id.isNull()) continue;
            const Transform* transform = registry.tryGet<Transform>(entities[i]);
            if (transform == nullptr) continue;
            rigidBody.id = world.createBody(
                toBodyDef(*transform, rigidBody, registry.tryGet<Collider>(entities[i])));
        }
    }

    if (ComponentPool<Joint>* joints = registry.findPool<Joint>()) {
        for (Joint& joint : joints->components()) {
            if (!joint.id.isNull()) continue;
            const std::optional<BodyId> body0 = jointSideBody(registry, joint.body0);
            const std::optional<BodyId> body1 = jointSideBody(registry, joint.body1);
            if (!body0 || !body1) continue;
            JointDef def = joint.def;
            def.body0 = *body0;
            def.body1 = *body1;
            joint.id = world.createJoint(def);
        }
    }
}

void PhysicsSystem::step(double dt) {
    sync();
    world_->step(dt);
    writeTransforms();
}

void PhysicsSystem::writeTransforms() {
    const World& world = *world_;
    registry_->view<RigidBody, Transform>().each(
        [&](const RigidBody& rigidBody, Transform& transform) {
            if (!world.isValid(rigidBody.id)) return;
            const Body& body = world.body(rigidBody.id);
            // A static body never moves: its Transform stays exactly what it was created from.
            if (!body.isDynamic()) return;
            transform.position = body.userPosition();
            transform.rotation = body.userOrientation();
        });
}

void PhysicsSystem::destroy(Entity entity) {
    Registry& registry = *registry_;
    World& world = *world_;
    if (!registry.isValid(entity)) return;

    // Joints on the entity or naming it lose their world joint; the world would drop those
    // attached to the body anyway, but their components must learn that their ids are dead.
    if (ComponentPool<Joint>* joints = registry.findPool<Joint>()) {
        const std::span<const Entity> owners = joints->entities();
        const std::span<Joint> components = joints->components();
        for (std::size_t i = 0; i < components.size(); ++i) {
            Joint& joint = components[i];
            if (owners[i] != entity && joint.body0 != entity && joint.body1 != entity) continue;
            world.destroyJoint(joint.id);
            joint.id = {};
        }
    }
    if (RigidBody* rigidBody = registry.tryGet<RigidBody>(entity)) {
        world.destroyBody(rigidBody->id);
        rigidBody->id = {};
    }
    registry.destroy(entity);
}

}  // namespace substep::ecs
