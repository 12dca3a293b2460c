// Contact benchmark scenes: PEERS.md's stack10 and spheres1000, and a pyramid, the tall-stack
// cases the paper names as its weakness (issue 3's "beyond the paper").

#include "scenes/scenes.h"

namespace substep::scenes {

/// stack10: 10 unit cubes of 1 kg on a ground plane, friction 0.5. Error measure: the top
/// cube's sideways drift.
SceneDescription stack10() {
    SceneDescription scene{.name = "stack10", .gravity = kPaperGravity, .substeps = 20, .iterations = 1};
    addGroundPlane(scene, 0.5);
    for (int i = 0; i < 10; ++i) {
        const size_t index = addBox(scene, "box" + std::to_string(i + 1), Vec3::Ones(), 1.0,
                                    Vec3(0.0, 0.5 + i, 0.0), Quat::Identity(), true);
        scene.bodies[index].def.staticFriction = 0.5;
        scene.bodies[index].def.dynamicFriction = 0.5;
    }
    scene.camera = SceneCamera{.position = Vec3(8.0, 6.0, 14.0), .target = Vec3(0.0, 4.5, 0.0)};
    return scene;
}

/// pyramid10: 10 rows of unit cubes (55 boxes of 1 kg), 5 cm apart within a row, friction 0.5.
SceneDescription pyramid10() {
    SceneDescription scene{.name = "pyramid10", .gravity = kPaperGravity, .substeps = 20, .iterations = 1};
    addGroundPlane(scene, 0.5);
    constexpr int kRows = 10;
    constexpr double kPitch = 1.05;
    for (int row = 0; row < kRows; ++row) {
        const int count = kRows - row;
        for (int i = 0; i < count; ++i) {
            const double x = (i - 0.5 * (count - 1)) * kPitch;
            // Appended, not `"r" + ... + "b" + ...`: GCC 12 warns falsely (-Wrestrict) on that chain.
            std::string name = "r";
            name += std::to_string(row + 1);
            name += 'b';
            name += std::to_string(i + 1);
            const size_t index = addBox(scene, name,
                                        Vec3::Ones(), 1.0, Vec3(x, 0.5 + row, 0.0),
                                        Quat::Identity(), true);
            scene.bodies[index].def.staticFriction = 0.5;
            scene.bodies[index].def.dynamicFriction = 0.5;
        }
    }
    scene.camera = SceneCamera{.position = Vec3(6.0, 7.0, 18.0), .target = Vec3(0.0, 4.0, 0.0)};
    return scene;
}

/// spheres1000: 1000 spheres (r 0.1, 1 kg) in a 10 x 10 x 10 grid dropped into a 3 x 3 m walled
/// box; friction 0.5, restitution 0.1. Error measure: the deepest penetration at the end.
SceneDescription spheres1000() {
    SceneDescription scene{.name = "spheres1000", .gravity = kPaperGravity, .substeps = 20, .iterations = 1};
    addGroundPlane(scene, 0.5, 0.1);
    constexpr double kInside = 3.0;
    constexpr double kWall = 0.2;
    constexpr double kHeight = 1.5;  // above the settled pile (about 0.8 m), low enough to see in
    for (int side = 0; side < 4; ++side) {
        const bool alongX = side < 2;
        const double offset = (side % 2 == 0 ? -1.0 : 1.0) * 0.5 * (kInside + kWall);
        const Vec3 size = alongX ? Vec3(kInside + 2 * kWall, kHeight, kWall) : Vec3(kWall, kHeight, kInside);
        const Vec3 position = alongX ? Vec3(0.0, 0.5 * kHeight, offset) : Vec3(offset, 0.5 * kHeight, 0.0);
        scene.bodies.push_back({"wall" + std::to_string(side + 1),
                                BodyDef{.shape = boxShape(size),
                                        .type = BodyType::Static,
                                        .position = position,
                                        .staticFriction = 0.5,
                                        .dynamicFriction = 0.5,
                                        .restitution = 0.1}});
    }
    constexpr double kPitch = 0.25;
    for (int y = 0; y < 10; ++y)
        for (int z = 0; z < 10; ++z)
            for (int x = 0; x < 10; ++x) {
                // A small shift per layer keeps the columns from landing exactly on top of one
                // another (a perfect column is a stack, not a pile).
                const double shift = 0.01 * (y % 3);
                scene.bodies.push_back(
                    {"", BodyDef{.shape = sphereShape(0.1),
                                 .mass = 1.0,
                                 .position = Vec3((x - 4.5) * kPitch + shift, 0.5 + y * kPitch, (z - 4.5) * kPitch - shift),
                                 .staticFriction = 0.5,
                                 .dynamicFriction = 0.5,
                                 .restitution = 0.1}});
            }
    scene.camera = SceneCamera{.position = Vec3(3.5, 6.5, 5.0), .target = Vec3(0.0, 0.4, 0.0)};
    return scene;
}

}  // namespace substep::scenes
