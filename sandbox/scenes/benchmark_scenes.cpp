// The shared benchmark scenes of PEERS.md that other engines were measured on: frame 1/60 s,
// gravity 10, the engines' own substeps. Built here exactly as PEERS.md describes them.

#include "scenes/scenes.h"

#include <cmath>

namespace substep::scenes {

/// chain100: 100 boxes (0.1 m, 1 kg) hanging at rest on ball joints 0.25 m apart from a world
/// anchor. Error measure: relative elongation of the chain.
SceneDescription chain100() {
    SceneDescription scene{.name = "chain100", .gravity = kPaperGravity, .substeps = 20, .iterations = 1};
    const Vec3 top(0.0, 30.0, 0.0);
    constexpr double kSpacing = 0.25;
    const Vec3 halfSpacing(0.0, kSpacing / 2, 0.0);
    for (int i = 0; i < 100; ++i) {
        const std::string name = "link" + std::to_string(i + 1);
        addBox(scene, name, Vec3(0.1, 0.1, 0.1), 1.0, top - Vec3(0.0, kSpacing * (i + 0.5), 0.0));
        JointDef ball{.type = JointType::Spherical, .anchor0 = -halfSpacing, .anchor1 = halfSpacing};
        if (i == 0) ball.anchor0 = top;
        addJoint(scene, "joint" + std::to_string(i + 1), i == 0 ? "" : "link" + std::to_string(i), name, ball);
    }
    scene.camera = SceneCamera{.position = Vec3(0.0, 17.5, 40.0), .target = Vec3(0.0, 17.5, 0.0)};
    return scene;
}

/// rope100: 100 capsules (radius 0.02, segment 0.1 m, 0.05 kg) end to end on ball joints, one
/// end fixed, released horizontal. Error measure: largest joint gap over the run.
SceneDescription rope100() {
    SceneDescription scene{.name = "rope100", .gravity = kPaperGravity, .substeps = 20, .iterations = 1};
    constexpr double kRadius = 0.02;
    constexpr double kSegment = 0.1;
    constexpr double kPitch = kSegment + 2 * kRadius;  // tip to tip
    const Vec3 start(0.0, 15.0, 0.0);
    // Capsules lie along local y; turning -90° about z lays them along world x.
    const Quat alongX(Eigen::AngleAxisd(-M_PI / 2, Vec3::UnitZ()));
    const Vec3 tip(0.0, kPitch / 2, 0.0);
    for (int i = 0; i < 100; ++i) {
        const std::string name = "segment" + std::to_string(i + 1);
        scene.bodies.push_back({name, BodyDef{.shape = capsuleShape(kRadius, kSegment),
                                              .mass = 0.05,
                                              .position = start + Vec3(kPitch * (i + 0.5), 0.0, 0.0),
                                              .orientation = alongX,
                                              .collide = false}});
        JointDef ball{.type = JointType::Spherical, .anchor0 = tip, .anchor1 = -tip};
        if (i == 0) ball.anchor0 = start;
        addJoint(scene, "joint" + std::to_string(i + 1), i == 0 ? "" : "segment" + std::to_string(i), name, ball);
    }
    scene.camera = SceneCamera{.position = Vec3(0.0, 8.0, 30.0), .target = Vec3(0.0, 8.0, 0.0)};
    return scene;
}

}  // namespace substep::scenes
