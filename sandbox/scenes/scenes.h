#pragma once
/// Builders of the built-in scenes, one per file in this folder; scene_registry.cpp lists them.
/// Each uses the paper's parameters where the paper gives them (gravity 10, Table 1 substeps).

#include "scenes/scene_registry.h"

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
SceneDescription stack10();    ///< PEERS.md stack10: 10 unit cubes stacked on the ground
SceneDescription pyramid10();  ///< a pyramid of 10 rows of unit cubes (55 boxes)
SceneDescription spheres1000();  ///< PEERS.md spheres1000: 1000 spheres dropped into a box

// The paper's gallery: each file defines its scene's whole entry (name, description, Table 1
// figure, builder and script), so a gallery scene lives in one file.
SceneEntry jointTypesEntry();     ///< Fig. 7 (joint_types.cpp)
SceneEntry bunnyChainEntry();     ///< Figs. 10-11 (bunny_chain.cpp)
SceneEntry cradleEntry();         ///< Fig. 12 (cradle.cpp)
SceneEntry marblesOnWireEntry();  ///< Fig. 13 (marbles_on_wire.cpp)
SceneEntry coinEntry();           ///< Fig. 15 (coin.cpp)
SceneEntry robotArmEntry();       ///< Fig. 17 (robot_arm.cpp)
SceneEntry twistedRopeEntry();    ///< Fig. 18 (twisted_rope.cpp)
SceneEntry rollingBallsEntry();   ///< Figs. 1, 14 (rolling_balls.cpp)
SceneEntry rcCarEntry();          ///< Figs. 1, 16 (rc_car.cpp, rc_car_script.cpp)

/// The paper's gravity (its demos use 10 m/s²).
inline const Vec3 kPaperGravity(0.0, -10.0, 0.0);

/// Adds a dynamic box and returns its index in description.bodies. It collides only when asked:
/// the joint demos (Figs. 4-8, PEERS' chains and pendulums) have no contacts, so their links
/// swing through one another and their figures stay the joints' alone.
inline size_t addBox(SceneDescription& scene, std::string name, const Vec3& size, double mass,
                     const Vec3& position, const Quat& orientation = Quat::Identity(),
                     bool collide = false) {
    scene.bodies.push_back({std::move(name), BodyDef{.shape = boxShape(size),
                                                     .mass = mass,
                                                     .position = position,
                                                     .orientation = orientation,
                                                     .collide = collide}});
    return scene.bodies.size() - 1;
}

/// Adds a static box (a ceiling or a mount) and returns its index; like addBox, no contacts.
inline size_t addStaticBox(SceneDescription& scene, std::string name, const Vec3& size,
                           const Vec3& position) {
    scene.bodies.push_back({std::move(name), BodyDef{.shape = boxShape(size),
                                                     .type = BodyType::Static,
                                                     .position = position,
                                                     .collide = false}});
    return scene.bodies.size() - 1;
}

/// Adds a static ground plane through the origin, facing up, named "ground".
inline void addGroundPlane(SceneDescription& scene, double friction, double restitution = 0.0) {
    scene.bodies.push_back({"ground", BodyDef{.shape = planeShape(Vec3::UnitY(), 0.0),
                                              .type = BodyType::Static,
                                              .staticFriction = friction,
                                              .dynamicFriction = friction,
                                              .restitution = restitution}});
}

/// Adds a joint between two named bodies ("" for the world).
inline void addJoint(SceneDescription& scene, std::string name, std::string body0,
                     std::string body1, const JointDef& def) {
    scene.joints.push_back({std::move(name), std::move(body0), std::move(body1), def});
}

}  // namespace substep::scenes
