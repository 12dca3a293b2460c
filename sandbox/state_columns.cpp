#include "state_columns.h"

#include "ecs/components.h"
#include "ecs/physics_system.h"
#include "ecs/soft_body_component.h"

#include <array>
#include <string_view>

namespace substep {

namespace {

constexpr std::array<std::string_view, 7> kWorldColumns = {
    "frame", "t", "kinetic", "potential", "elastic", "energy", "max_error"};
constexpr std::array<std::string_view, 13> kBodyColumns = {"x",  "y",  "z",  "qw", "qx", "qy", "qz",
                                                           "vx", "vy", "vz", "wx", "wy", "wz"};
constexpr std::array<std::string_view, 3> kJointColumns = {"force", "torque", "error"};
constexpr std::array<std::string_view, 10> kSoftBodyColumns = {"x",  "y",  "z",  "vx", "vy",
                                                               "vz", "ex", "ey", "ez", "volume"};

/// The named entities among `entities` (description order), with their names.
template <class Visit>
void forEachNamed(const SceneInstance& scene, const std::vector<ecs::Entity>& entities, Visit&& visit) {
    for (const ecs::Entity entity : entities)
        if (const ecs::Name* name = scene.registry.tryGet<ecs::Name>(entity)) visit(entity, name->value);
}

std::size_t namedCount(const SceneInstance& scene, const std::vector<ecs::Entity>& entities) {
    std::size_t count = 0;
    forEachNamed(scene, entities, [&](ecs::Entity, const std::string&) { ++count; });
    return count;
}

std::size_t sampledColumnCount(const SceneInstance& scene) {
    return kWorldColumns.size() - 1 + kBodyColumns.size() * namedCount(scene, scene.bodyEntities) +
           kJointColumns.size() * namedCount(scene, scene.jointEntities) +
           kSoftBodyColumns.size() * namedCount(scene, scene.softBodyEntities);
}

}  // namespace

std::vector<std::string> stateColumnNames(const SceneInstance& scene) {
    std::vector<std::string> names;
    names.reserve(sampledColumnCount(scene) + 1);
    for (const std::string_view column : kWorldColumns)
        names.emplace_back(column);
    forEachNamed(scene, scene.bodyEntities, [&](ecs::Entity, const std::string& name) {
        for (const std::string_view column : kBodyColumns) names.push_back(name + "." + std::string(column));
    });
    forEachNamed(scene, scene.jointEntities, [&](ecs::Entity, const std::string& name) {
        for (const std::string_view column : kJointColumns) names.push_back(name + "." + std::string(column));
    });
    forEachNamed(scene, scene.softBodyEntities, [&](ecs::Entity, const std::string& name) {
        for (const std::string_view column : kSoftBodyColumns) names.push_back(name + "." + std::string(column));
    });
    return names;
}

void sampleState(const SceneInstance& scene, double t, std::vector<double>& values) {
    values.resize(sampledColumnCount(scene));
    // Energies and the largest joint error are measures of the whole world; everything per body
    // and per joint is read from the components the physics system wrote after the last step.
    const World& world = scene.world();
    const Energies energies = world.energies();
    auto out = values.begin();
    *out++ = t;
    *out++ = energies.kinetic;
    *out++ = energies.potential;
    *out++ = energies.elastic;
    *out++ = energies.total();
    *out++ = world.maxJointError();

    // Poses of the user frame (the one scene files and anchors use), not the principal frame.
    const ecs::Registry& registry = scene.registry;
    forEachNamed(scene, scene.bodyEntities, [&](ecs::Entity entity, const std::string&) {
        const ecs::Transform& transform = registry.get<ecs::Transform>(entity);
        const ecs::RigidBody& body = registry.get<ecs::RigidBody>(entity);
        const Vec3& position = transform.position;
        const Quat& orientation = transform.rotation;
        for (const double value :
             {position.x(), position.y(), position.z(), orientation.w(), orientation.x(),
              orientation.y(), orientation.z(), body.velocity.x(), body.velocity.y(),
              body.velocity.z(), body.angularVelocity.x(), body.angularVelocity.y(),
              body.angularVelocity.z()}) {
            *out++ = value;
        }
    });
    forEachNamed(scene, scene.jointEntities, [&](ecs::Entity entity, const std::string&) {
        const JointReadout& readout = registry.get<ecs::Joint>(entity).readout;
        *out++ = readout.force;
        *out++ = readout.torque;
        *out++ = readout.error;
    });
    forEachNamed(scene, scene.softBodyEntities, [&](ecs::Entity entity, const std::string&) {
        const SoftBodyReadout readout = ecs::softBodyReadout(scene.world(), registry.get<ecs::SoftBody>(entity));
        for (const double value :
             {readout.centreOfMass.x(), readout.centreOfMass.y(), readout.centreOfMass.z(),
              readout.velocity.x(), readout.velocity.y(), readout.velocity.z(), readout.extent.x(),
              readout.extent.y(), readout.extent.z(), readout.volume}) {
            *out++ = value;
        }
    });
}

}  // namespace substep
