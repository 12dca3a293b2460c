#pragma once
/// Builders of the built-in scenes, one per file in this folder; scene_registry.cpp lists them.
/// Each uses the paper's parameters where the paper gives them (gravity 10, Table 1 substeps).

#include "scene/scene.h"

namespace substep::scenes {

SceneDescription boxes3();     ///< Fig. 4: three boxes on springs of compliance 0.01
SceneDescription boxes7();     ///< Fig. 4: seven boxes on springs of compliance 0.01
SceneDescription hingeBar();   ///< Fig. 5: a bar held level by a hinge with target angle 0
SceneDescription massRatio();  ///< Fig. 6: 1 g boxes holding 1 kg boxes, three compliances
SceneDescription pendula();    ///< Fig. 8: double, triple and closed-loop pendulum
SceneDescription pendulum3();  ///< PEERS.md pendulum3: triple pendulum released horizontal
SceneDescription chain100();   ///< PEERS.md chain100: 100 boxes on ball joints, at rest
SceneDescription rope100();    ///< PEERS.md rope100: 100 capsules released horizontal

/// The paper's gravity (its demos use 10 m/s²).
inline const Vec3 kPaperGravity(0.0, -10.0, 0.0);

/// Adds a dynamic box and returns its index in description.bodies.
inline size_t addBox(SceneDescription& scene, std::string name, const Vec3& size, double mass,
                     const Vec3& position, const Quat& orientation = Quat::Identity()) {
    scene.bodies.push_back({std::move(name), BodyDef{.shape = boxShape(size),
                                                     .mass = mass,
                                                     .position = position,
                                                     .orientation = orientation}});
    return scene.bodies.size() - 1;
}

/// Adds a static box (a ceiling or a mount) and returns its index.
inline size_t addStaticBox(SceneDescription& scene, std::string name, const Vec3& size,
                           const Vec3& position) {
    scene.bodies.push_back(
        {std::move(name),
         BodyDef{.shape = boxShape(size), .type = BodyType::Static, .position = position}});
    return scene.bodies.size() - 1;
}

/// Adds a joint between two named bodies ("" for the world).
inline void addJoint(SceneDescription& scene, std::string name, std::string body0,
                     std::string body1, const JointDef& def) {
    scene.joints.push_back({std::move(name), std::move(body0), std::move(body1), def});
}

}  // namespace substep::scenes
