#include "state_columns.h"

#include <array>
#include <string_view>

namespace substep {

namespace {

constexpr std::array<std::string_view, 7> kWorldColumns = {
    "frame", "t", "kinetic", "potential", "elastic", "energy", "max_error"};
constexpr std::array<std::string_view, 13> kBodyColumns = {"x",  "y",  "z",  "qw", "qx", "qy", "qz",
                                                           "vx", "vy", "vz", "wx", "wy", "wz"};
constexpr std::array<std::string_view, 3> kJointColumns = {"force", "torque", "error"};

std::size_t sampledColumnCount(const SceneInstance& scene) {
    return kWorldColumns.size() - 1 + kBodyColumns.size() * scene.namedBodies.size() +
           kJointColumns.size() * scene.namedJoints.size();
}

}  // namespace

std::vector<std::string> stateColumnNames(const SceneInstance& scene) {
    std::vector<std::string> names;
    names.reserve(sampledColumnCount(scene) + 1);
    for (const std::string_view column : kWorldColumns)
        names.emplace_back(column);
    for (const auto& [name, id] : scene.namedBodies) {
        for (const std::string_view column : kBodyColumns) {
            names.push_back(name + "." + std::string(column));
        }
    }
    for (const auto& [name, id] : scene.namedJoints) {
        for (const std::string_view column : kJointColumns) {
            names.push_back(name + "." + std::string(column));
        }
    }
    return names;
}

void sampleState(const SceneInstance& scene, double t, std::vector<double>& values) {
    values.resize(sampledColumnCount(scene));
    const World& world = scene.world;
    const Energies energies = world.energies();
    auto out = values.begin();
    *out++ = t;
    *out++ = energies.kinetic;
    *out++ = energies.potential;
    *out++ = energies.elastic;
    *out++ = energies.total();
    *out++ = world.maxJointError();

    // Poses of the user frame (the one scene files and anchors use), not the principal frame.
    for (const auto& [name, id] : scene.namedBodies) {
        const Body& body = world.body(id);
        const Vec3 position = body.userPosition();
        const Quat orientation = body.userOrientation();
        for (const double value :
             {position.x(), position.y(), position.z(), orientation.w(), orientation.x(),
              orientation.y(), orientation.z(), body.v.x(), body.v.y(), body.v.z(), body.omega.x(),
              body.omega.y(), body.omega.z()}) {
            *out++ = value;
        }
    }
    for (const auto& [name, id] : scene.namedJoints) {
        const JointReadout readout = world.jointReadout(id);
        *out++ = readout.force;
        *out++ = readout.torque;
        *out++ = readout.error;
    }
}

}  // namespace substep
