/// PhysicsSystem: components -> world objects, patched components -> world changes, world state
/// -> components.

#include "ecs/physics_system.h"

#include "physics/step_cancellation.h"
#include "physics/world_snapshot.h"

#include "ecs/body_components.h"
#include "ecs/components.h"

#include "physics/soft/soft_system.h"

#include <cstddef>
#include <limits>
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

/// The patched entities of T's pool (empty without a pool), taken out of it.
template <class T>
void takeChanged(Registry& registry, std::vector<Entity>& out) {
    out.clear();
    if (ComponentPool<T>* pool = registry.findPool<T>()) pool->takeChanged(out);
}

/// Whether any component of T was patched since the last sync.
template <class T>
bool anyPatched(Registry& registry) {
    const ComponentPool<T>* pool = registry.findPool<T>();
    return pool != nullptr && pool->anyChanged();
}

/// Writes a body's simulated state into its components.
void writeBody(const Body& body, RigidBody& rigidBody, Transform* transform) {
    rigidBody.velocity = body.v;
    rigidBody.angularVelocity = body.omega;
    rigidBody.centreOfMass = body.x;
    if (transform != nullptr) {
        transform->position = body.userPosition();
        transform->rotation = body.userOrientation();
    }
}

}  // namespace

void PhysicsSystem::sync() {
    createNewObjects();
    applyChanges();
}

void PhysicsSystem::createNewObjects() {
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
            const Body& body = world.body(rigidBody.id);
            rigidBody.centreOfMass = body.x;
            rigidBody.simulatedMass = body.isDynamic() ? body.mass : 0.0;
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

    // Soft bodies last: their attachments name bodies, which now exist.
    if (ComponentPool<SoftBody>* softBodies = registry.findPool<SoftBody>()) {
        for (SoftBody& softBody : softBodies->components()) {
            if (!softBody.id.isNull()) continue;
            SoftBodyDef def = softBody.def;
            bool bodiesReady = softBody.attachedBodies.size() == def.attachments.size();
            for (std::size_t i = 0; bodiesReady && i < def.attachments.size(); ++i) {
                const std::optional<BodyId> body = jointSideBody(registry, softBody.attachedBodies[i]);
                // An attachment to the world is not a soft-body concept: a null entity waits too.
                bodiesReady = body.has_value() && !body->isNull();
                if (bodiesReady) def.attachments[i].body = *body;
            }
            if (!bodiesReady) continue;
            softBody.id = world.createSoftBody(def);
            softBody.readout = world.softBodyReadout(softBody.id);
        }
    }
}

void PhysicsSystem::applyChanges() {
    Registry& registry = *registry_;
    World& world = *world_;
    // A SoftBody is fixed at creation: its patches change nothing, and are dropped so that they
    // do not pile up.
    if (anyPatched<SoftBody>(registry)) {
        std::vector<Entity> ignored;
        takeChanged<SoftBody>(registry, ignored);
    }
    // Most steps of most scenes change nothing: they pay four tests.
    if (!anyPatched<Transform>(registry) && !anyPatched<RigidBody>(registry) &&
        !anyPatched<Collider>(registry) && !anyPatched<Joint>(registry))
        return;
    std::vector<Entity> changed;

    // Poses before velocities: a script that places a body and sets it moving gets both.
    takeChanged<Transform>(registry, changed);
    for (const Entity entity : changed) {
        RigidBody* rigidBody = registry.tryGet<RigidBody>(entity);
        Transform* transform = registry.tryGet<Transform>(entity);
        if (rigidBody == nullptr || transform == nullptr || !world.isValid(rigidBody->id)) continue;
        world.setBodyPose(rigidBody->id, transform->position, transform->rotation);
        // The Transform reads back as the world has it (the same pose, within rounding), as it
        // does after every step. Velocities are left alone: a patch of them may follow.
        const Body& body = world.body(rigidBody->id);
        transform->position = body.userPosition();
        transform->rotation = body.userOrientation();
        rigidBody->centreOfMass = body.x;
    }
    takeChanged<RigidBody>(registry, changed);
    for (const Entity entity : changed) {
        const RigidBody* rigidBody = registry.tryGet<RigidBody>(entity);
        if (rigidBody == nullptr || !world.isValid(rigidBody->id)) continue;
        world.setBodyVelocity(rigidBody->id, rigidBody->velocity, rigidBody->angularVelocity);
    }
    takeChanged<Collider>(registry, changed);
    for (const Entity entity : changed) {
        const RigidBody* rigidBody = registry.tryGet<RigidBody>(entity);
        const Collider* collider = registry.tryGet<Collider>(entity);
        if (rigidBody == nullptr || collider == nullptr || !world.isValid(rigidBody->id)) continue;
        world.setBodySurface(rigidBody->id, collider->staticFriction, collider->dynamicFriction,
                             collider->restitution, collider->collide);
    }
    takeChanged<Joint>(registry, changed);
    for (const Entity entity : changed) {
        const Joint* joint = registry.tryGet<Joint>(entity);
        if (joint == nullptr || !world.isValid(joint->id)) continue;
        world.updateJoint(joint->id, joint->def);
    }
}

std::chrono::steady_clock::duration PhysicsSystem::step(double dt) {
    sync();
    const auto start = std::chrono::steady_clock::now();
    world_->step(dt);
    const auto elapsed = std::chrono::steady_clock::now() - start;
    writeBack();
    return elapsed;
}

void PhysicsSystem::beginFrame(double dt) {
    sync();
    world_->beginFrame(dt);
}

bool PhysicsSystem::substep() {
    const bool stepped = world_->substep();
    if (stepped) writeBack();
    return stepped;
}

std::chrono::steady_clock::duration PhysicsSystem::finishFrame() {
    const auto start = std::chrono::steady_clock::now();
    while (world_->frameOpen() && world_->frameSubstepsDone() < world_->frameSubsteps()) {
        if (stepCancellationRequested()) break;  // as World::step: the caller discards the world
        world_->substep();
    }
    world_->endFrame();
    const auto elapsed = std::chrono::steady_clock::now() - start;
    writeBack();
    return elapsed;
}

void PhysicsSystem::writeBack() {
    const World& world = *world_;
    if (ComponentPool<RigidBody>* rigidBodies = registry_->findPool<RigidBody>()) {
        const std::span<const Entity> entities = rigidBodies->entities();
        const std::span<RigidBody> components = rigidBodies->components();
        ComponentPool<Transform>* transforms = registry_->findPool<Transform>();
        for (std::size_t i = 0; i < components.size(); ++i) {
            RigidBody& rigidBody = components[i];
            if (!world.isValid(rigidBody.id)) continue;
            const Body& body = world.body(rigidBody.id);
            // Static bodies are written too: what a reader sees is the world's pose of the
            // body's user frame, the same bits a dynamic body's pose has.
            writeBody(body, rigidBody, transforms != nullptr ? transforms->tryGet(entities[i]) : nullptr);
        }
    }
    if (ComponentPool<Joint>* joints = registry_->findPool<Joint>()) {
        for (Joint& joint : joints->components())
            joint.readout = world.isValid(joint.id) ? world.jointReadout(joint.id) : JointReadout{};
    }
    if (ComponentPool<SoftBody>* softBodies = registry_->findPool<SoftBody>()) {
        // The volume only on demand (softBodyReadout): NaN, so that a reader who forgot shows.
        for (SoftBody& softBody : softBodies->components()) {
            softBody.readout = world.isValid(softBody.id) ? world.softBodies()->readout(softBody.id, false) : SoftBodyReadout{};
            if (world.isValid(softBody.id)) softBody.readout.volume = std::numeric_limits<double>::quiet_NaN();
        }
    }
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
            joint.readout = {};
        }
    }
    if (RigidBody* rigidBody = registry.tryGet<RigidBody>(entity)) {
        world.destroyBody(rigidBody->id);
        rigidBody->id = {};
    }
    if (SoftBody* softBody = registry.tryGet<SoftBody>(entity)) {
        world.destroySoftBody(softBody->id);
        softBody->id = {};
    }
    registry.destroy(entity);
}

SoftBodyReadout softBodyReadout(const World& world, const SoftBody& softBody) {
    return world.isValid(softBody.id) ? world.softBodyReadout(softBody.id) : SoftBodyReadout{};
}

WorldSnapshot PhysicsSystem::snapshot() const { return world_->snapshot(); }

void PhysicsSystem::restore(const WorldSnapshot& snapshot) {
    world_->restore(snapshot);
    writeBack();
}

}  // namespace substep::ecs
