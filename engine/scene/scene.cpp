/// buildScene: a SceneDescription (from a file or a built-in scene) becomes a World.

#include "scene/scene.h"

#include <stdexcept>
#include <string>
#include <unordered_map>

namespace substep {

SceneInstance buildScene(const SceneDescription& description) {
    SceneInstance instance{
        .world = World(WorldSettings{.gravity = description.gravity,
                                     .substeps = description.substeps,
                                     .iterations = description.iterations}),
        .namedBodies = {},
        .namedJoints = {},
    };
    World& world = instance.world;

    // Bodies in order; named ones are remembered for joints and, in order, for output columns.
    std::unordered_map<std::string, BodyId> bodiesByName;
    for (const SceneBody& body : description.bodies) {
        const BodyId id = world.createBody(body.def);
        if (body.name.empty()) continue;
        // "world" would be ambiguous in joints, and a repeated name would repeat CSV columns.
        if (body.name == "world" || !bodiesByName.emplace(body.name, id).second) {
            throw std::invalid_argument("scene " + description.name + ": body name \"" + body.name +
                                        "\" is reserved or used twice");
        }
        instance.namedBodies.emplace_back(body.name, id);
    }

    // Empty or "world" is the world, which JointDef spells as a null id.
    const auto resolve = [&](const std::string& name) -> BodyId {
        if (name.empty() || name == "world") return BodyId{};
        const auto it = bodiesByName.find(name);
        if (it == bodiesByName.end()) {
            throw std::invalid_argument("scene " + description.name + ": a joint names body \"" +
                                        name + "\", which does not exist");
        }
        return it->second;
    };

    for (const SceneJoint& joint : description.joints) {
        JointDef def = joint.def;
        def.body0 = resolve(joint.body0);
        def.body1 = resolve(joint.body1);
        const JointId id = world.createJoint(def);
        if (!joint.name.empty()) instance.namedJoints.emplace_back(joint.name, id);
    }
    return instance;
}

}  // namespace substep
