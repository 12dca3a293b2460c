/// buildScene: a SceneDescription (from a file or a built-in scene) becomes entities, and the
/// physics system makes the World from them.

#include "scene/scene.h"

#include "ecs/body_components.h"
#include "ecs/components.h"
#include "ecs/soft_body_component.h"

#include <array>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace substep {

namespace {

/// A default look per body until scene files carry colours: static bodies grey, moving ones
/// from a small palette in description order, so neighbours differ.
Vec3 defaultColour(std::size_t bodyIndex, const BodyDef& def) {
    static constexpr std::array<std::array<double, 3>, 6> kPalette{{
        {0.86, 0.42, 0.27},  // terracotta
        {0.29, 0.56, 0.85},  // blue
        {0.95, 0.77, 0.30},  // yellow
        {0.40, 0.73, 0.45},  // green
        {0.62, 0.47, 0.80},  // violet
        {0.30, 0.75, 0.75},  // teal
    }};
    if (def.type == BodyType::Static) return Vec3(0.55, 0.55, 0.58);
    const std::array<double, 3>& c = kPalette[bodyIndex % kPalette.size()];
    return Vec3(c[0], c[1], c[2]);
}

/// Soft bodies' default look: a rubbery dark slate, apart from the rigid palette.
const Vec3 kSoftBodyColour(0.30, 0.32, 0.36);

}  // namespace

SceneInstance buildScene(const SceneDescription& description) {
    SceneInstance instance(World(WorldSettings{.gravity = description.gravity,
                                               .substeps = description.substeps,
                                               .iterations = description.iterations,
                                               .sleeping = description.sleeping,
                                               .jointProjection = description.jointProjection,
                                               .sweptRestitution = description.sweptRestitution,
                                               .softPatchFriction = description.softPatchFriction,
                                               .softHeldContacts = description.softHeldContacts}));
    ecs::Registry& registry = instance.registry;

    // One entity per body, in order; named ones are remembered for joints.
    std::unordered_map<std::string, ecs::Entity> entitiesByName;
    for (std::size_t i = 0; i < description.bodies.size(); ++i) {
        const SceneBody& body = description.bodies[i];
        const ecs::Entity entity = registry.create();
        ecs::emplaceBody(registry, entity, body.def);
        registry.emplace<ecs::RenderMaterial>(
            entity, ecs::RenderMaterial{.colour = body.colour.value_or(defaultColour(i, body.def))});
        instance.bodyEntities.push_back(entity);
        if (body.name.empty()) continue;
        // "world" would be ambiguous in joints, and a repeated name would repeat CSV columns.
        if (body.name == "world" || !entitiesByName.emplace(body.name, entity).second) {
            throw std::invalid_argument("scene " + description.name + ": body name \"" + body.name +
                                        "\" is reserved or used twice");
        }
        registry.emplace<ecs::Name>(entity, body.name);
    }

    // Empty or "world" is the world, which a Joint component spells as the null entity.
    const auto resolve = [&](const std::string& name) -> ecs::Entity {
        if (name.empty() || name == "world") return ecs::kNullEntity;
        const auto it = entitiesByName.find(name);
        if (it == entitiesByName.end()) {
            throw std::invalid_argument("scene " + description.name + ": a joint names body \"" +
                                        name + "\", which does not exist");
        }
        return it->second;
    };

    for (const SceneJoint& joint : description.joints) {
        const ecs::Entity body0 = resolve(joint.body0);
        const ecs::Entity body1 = resolve(joint.body1);
        const ecs::Entity entity = registry.create();
        registry.emplace<ecs::Joint>(entity,
                                     ecs::Joint{.def = joint.def, .body0 = body0, .body1 = body1});
        if (!joint.name.empty()) registry.emplace<ecs::Name>(entity, joint.name);
        instance.jointEntities.push_back(entity);
    }

    // Soft bodies attach to named bodies; "world" is not a body they can hold on to.
    std::unordered_map<std::string, ecs::Entity> softBodiesByName;
    for (const SceneSoftBody& softBody : description.softBodies) {
        if (softBody.attachBodies.size() != softBody.def.attachments.size()) {
            throw std::invalid_argument("scene " + description.name + ": soft body \"" + softBody.name +
                                        "\" has " + std::to_string(softBody.def.attachments.size()) +
                                        " attachments but " + std::to_string(softBody.attachBodies.size()) +
                                        " body names");
        }
        ecs::SoftBody component{.def = softBody.def};
        for (const std::string& bodyName : softBody.attachBodies) {
            const auto it = entitiesByName.find(bodyName);
            if (it == entitiesByName.end()) {
                throw std::invalid_argument("scene " + description.name + ": a soft body attaches to body \"" +
                                            bodyName + "\", which does not exist");
            }
            component.attachedBodies.push_back(it->second);
        }
        const ecs::Entity entity = registry.create();
        registry.emplace<ecs::SoftBody>(entity, std::move(component));
        registry.emplace<ecs::RenderMaterial>(entity,
                                              ecs::RenderMaterial{.colour = softBody.colour.value_or(kSoftBodyColour)});
        instance.softBodyEntities.push_back(entity);
        if (softBody.name.empty()) continue;
        if (!softBodiesByName.emplace(softBody.name, entity).second) {
            throw std::invalid_argument("scene " + description.name + ": soft body name \"" + softBody.name +
                                        "\" is used twice");
        }
        registry.emplace<ecs::Name>(entity, softBody.name);
    }

    // The system creates every body, then every joint, then every soft body, each in the order
    // added above.
    // Components then read back the initial state as the world holds it.
    ecs::PhysicsSystem physics = instance.physics();
    physics.sync();
    physics.writeBack();

    return instance;
}

namespace {

/// The entity among `entities` whose Name is `name`, or the null entity.
ecs::Entity findNamed(const ecs::Registry& registry, const std::vector<ecs::Entity>& entities,
                     std::string_view name) {
    for (const ecs::Entity entity : entities) {
        const ecs::Name* entityName = registry.tryGet<ecs::Name>(entity);
        if (entityName != nullptr && entityName->value == name) return entity;
    }
    return ecs::kNullEntity;
}

}  // namespace

ecs::Entity SceneInstance::bodyNamed(std::string_view name) const {
    return findNamed(registry, bodyEntities, name);
}

ecs::Entity SceneInstance::jointNamed(std::string_view name) const {
    return findNamed(registry, jointEntities, name);
}

ecs::Entity SceneInstance::softBodyNamed(std::string_view name) const {
    return findNamed(registry, softBodyEntities, name);
}

BodyId SceneInstance::bodyIdNamed(std::string_view name) const {
    const ecs::Entity entity = bodyNamed(name);
    const ecs::RigidBody* body = entity.isNull() ? nullptr : registry.tryGet<ecs::RigidBody>(entity);
    return body != nullptr ? body->id : BodyId{};
}

JointId SceneInstance::jointIdNamed(std::string_view name) const {
    const ecs::Entity entity = jointNamed(name);
    const ecs::Joint* joint = entity.isNull() ? nullptr : registry.tryGet<ecs::Joint>(entity);
    return joint != nullptr ? joint->id : JointId{};
}

std::vector<std::pair<std::string, BodyId>> SceneInstance::namedBodyIds() const {
    std::vector<std::pair<std::string, BodyId>> named;
    for (const ecs::Entity entity : bodyEntities) {
        const ecs::Name* name = registry.tryGet<ecs::Name>(entity);
        const ecs::RigidBody* body = registry.tryGet<ecs::RigidBody>(entity);
        if (name != nullptr && body != nullptr) named.emplace_back(name->value, body->id);
    }
    return named;
}

std::vector<std::pair<std::string, JointId>> SceneInstance::namedJointIds() const {
    std::vector<std::pair<std::string, JointId>> named;
    for (const ecs::Entity entity : jointEntities) {
        const ecs::Name* name = registry.tryGet<ecs::Name>(entity);
        const ecs::Joint* joint = registry.tryGet<ecs::Joint>(entity);
        if (name != nullptr && joint != nullptr) named.emplace_back(name->value, joint->id);
    }
    return named;
}

}  // namespace substep
