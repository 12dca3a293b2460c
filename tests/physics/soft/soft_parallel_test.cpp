// Tests the soft bodies' solve on the worker pool (soft_system.cpp's planShares, solvePositions,
// solveVelocities; soft_contacts.cpp's findContacts): where no moving rigid body is held or
// touched by two soft bodies, each body's contacts, elements, attachments and velocity pass run
// on a thread of their own, with the bytes of one thread; where one is, the bodies are solved
// together, as on one thread. Rims that carry tyres and a loose box that one tyre runs into, and
// a plank that rests on two soft boxes, at 1, 2 and 3 threads, compared bit for bit.
#include "soft_test_support.h"

#include "physics_test_support.h"

#include <gtest/gtest.h>

#include <cstring>
#include <vector>

namespace substep::test {
namespace {

/// Turns local y (the axis of cylinders and tyres) into world z.
const Quat kAxisAlongZ(Eigen::AngleAxisd(kPi / 2, Vec3::UnitX()));

struct Scene {
    World world;
    std::vector<SoftBodyId> soft;
    std::vector<BodyId> rigid;
};

World worldWithThreads(int threads) {
    World world = worldWithGround();
    WorldSettings settings = world.settings();
    settings.threads = threads;
    world.setSettings(settings);
    return world;
}

/// Three tyres on free rims of different masses and spins, rolling on the ground, and a loose
/// box in the path of the first.
Scene rollingTyres(int threads) {
    Scene scene{.world = worldWithThreads(threads)};
    World& world = scene.world;
    const double ro = 0.2, ri = 0.13, width = 0.1;
    for (int k = 0; k < 3; ++k) {
        const Vec3 centre(1.5 * k, ro + 0.01, 0.0);
        const Vec3 spin(0.0, 0.0, -4.0 - 3.0 * k);
        const Vec3 velocity = spin.cross(Vec3(0.0, ro, 0.0));  // rolling: the contact point at rest
        const BodyId rim = world.createBody({.shape = cylinderShape(ri, width),
                                             .density = 800.0 + 500.0 * k,
                                             .position = centre,
                                             .orientation = kAxisAlongZ,
                                             .velocity = velocity,
                                             .angularVelocity = spin});
        SoftBodyDef tyre{.type = SoftBodyType::Tyre,
                         .outerRadius = ro,
                         .innerRadius = ri,
                         .width = width,
                         .cells = {20 + 4 * k, 2, 2},
                         .position = centre,
                         .orientation = kAxisAlongZ,
                         .velocity = velocity,
                         .angularVelocity = spin,
                         .compliance = 1e-6 * (k + 1)};
        tyre.attachments.push_back({.body = rim, .particles = SoftAttachmentParticles::Inner});
        scene.soft.push_back(world.createSoftBody(tyre));
        scene.rigid.push_back(rim);
    }
    // In the first tyre's way: its contacts move a body, which no other tyre touches.
    scene.rigid.push_back(world.createBody(
        {.shape = boxShape(Vec3(0.15, 0.15, 0.3)), .mass = 0.4, .position = Vec3(0.45, 0.076, 0.0)}));
    return scene;
}

/// A plank resting on two soft boxes: both boxes' contacts move it.
Scene plankOnTwoBoxes(int threads) {
    Scene scene{.world = worldWithThreads(threads)};
    World& world = scene.world;
    for (int k = 0; k < 2; ++k)
        scene.soft.push_back(world.createSoftBody({.size = Vec3(0.2, 0.2, 0.2),
                                                   .cells = {2, 2, 2},
                                                   .position = Vec3(-0.3 + 0.6 * k, 0.105, 0.0),
                                                   .compliance = 1e-6 * (k + 1)}));
    scene.rigid.push_back(world.createBody(
        {.shape = boxShape(Vec3(1.0, 0.05, 0.3)), .mass = 2.0, .position = Vec3(0.05, 0.24, 0.0)}));
    return scene;
}

/// Whether `b` has the bytes of `a`: its soft bodies' particles and its rigid bodies.
bool sameBytes(const Scene& a, const Scene& b) {
    for (size_t s = 0; s < a.soft.size(); ++s) {
        const auto x = a.world.softBodyPositions(a.soft[s]), y = b.world.softBodyPositions(b.soft[s]);
        const auto v = a.world.softBodies()->velocities(a.soft[s]), w = b.world.softBodies()->velocities(b.soft[s]);
        if (x.size() != y.size() || std::memcmp(x.data(), y.data(), x.size() * sizeof(Vec3)) != 0 ||
            std::memcmp(v.data(), w.data(), v.size() * sizeof(Vec3)) != 0)
            return false;
    }
    return differingBodies(a.world, b.world) == 0;
}

/// Steps the scene at 1, 2 and 3 threads, comparing every frame; returns how many frames of the
/// threaded worlds had their soft bodies apart.
int framesApartComparing(Scene (*make)(int), int frames) {
    std::vector<Scene> scenes;
    for (const int threads : {1, 2, 3}) scenes.push_back(make(threads));
    int apart = 0;
    for (int frame = 0; frame < frames; ++frame) {
        for (Scene& scene : scenes) scene.world.step(kDt);
        EXPECT_FALSE(scenes[0].world.softBodies()->bodiesApart()) << "one thread plans no shares";
        apart += scenes[1].world.softBodies()->bodiesApart() ? 1 : 0;
        EXPECT_EQ(scenes[1].world.softBodies()->bodiesApart(), scenes[2].world.softBodies()->bodiesApart());
        for (size_t w = 1; w < scenes.size(); ++w)
            if (!sameBytes(scenes[0], scenes[w])) {
                ADD_FAILURE() << w + 1 << " threads differ from one at frame " << frame;
                return apart;
            }
    }
    EXPECT_TRUE(scenes[0].world.isFinite());
    return apart;
}

TEST(SoftParallel, TyresOnTheirOwnRimsGiveOneThreadsBytes) {
    const int frames = 60;
    const int apart = framesApartComparing(rollingTyres, frames);
    // Every frame: each tyre holds its own rim and the box is the first tyre's alone.
    EXPECT_EQ(apart, frames);
    // The box was hit (its contacts took the moving body's path) and the tyres rolled.
    Scene scene = rollingTyres(2);
    runFor(scene.world, 0.5);
    EXPECT_GT(scene.world.body(scene.rigid.back()).x.x(), 0.5);
    EXPECT_GT(scene.world.activeContactCount(), 10);
}

TEST(SoftParallel, BodiesUnderOnePlankAreSolvedTogether) {
    const int frames = 40;
    const int apart = framesApartComparing(plankOnTwoBoxes, frames);
    // Once the plank rests on both boxes they are not apart (the first frames, before it
    // touches both, may be).
    Scene scene = plankOnTwoBoxes(2);
    runFor(scene.world, 0.3);
    EXPECT_FALSE(scene.world.softBodies()->bodiesApart());
    EXPECT_LT(apart, frames);
    EXPECT_NEAR(scene.world.body(scene.rigid[0]).x.y(), 0.225, 0.02);  // resting on the boxes
}

TEST(SoftParallel, BodiesCreatedAndDestroyedBetweenSubstepsKeepOneThreadsBytes) {
    // The window steps one substep at a time, and a soft body may come or go between two: the
    // next substeps plan their shares afresh (a body created mid-frame has no candidates until
    // the next frame), with the bytes of one thread.
    std::vector<Scene> scenes;
    for (const int threads : {1, 2}) scenes.push_back(rollingTyres(threads));
    int apartWithTheNewBody = 0;
    for (int frame = 0; frame < 12; ++frame) {
        for (Scene& scene : scenes) {
            World& world = scene.world;
            world.beginFrame(kDt);
            for (int k = 0; k < 7; ++k) world.substep();
            if (frame == 3)
                scene.soft.push_back(world.createSoftBody({.size = Vec3(0.2, 0.2, 0.2), .cells = {2, 2, 2},
                                                           .position = Vec3(3.5, 0.2, 0.0), .compliance = 1e-6}));
            if (frame == 8) {
                world.destroySoftBody(scene.soft[1]);
                scene.soft.erase(scene.soft.begin() + 1);
            }
            while (world.substep()) {
            }
            world.endFrame();
        }
        if (frame >= 4 && frame < 8) apartWithTheNewBody += scenes[1].world.softBodies()->bodiesApart() ? 1 : 0;
        ASSERT_TRUE(sameBytes(scenes[0], scenes[1])) << "frame " << frame;
    }
    EXPECT_TRUE(scenes[1].world.isFinite());
    EXPECT_GT(apartWithTheNewBody, 0);  // the new body's share was solved on the pool
}

}  // namespace
}  // namespace substep::test
