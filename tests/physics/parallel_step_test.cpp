// Tests engine/physics/world_parallel.cpp (WorldSettings::threads, colouredSolve): a pile, a
// grid of stacks and jointed chains falling on the ground step to the same bytes at 2, 3 and 4
// threads as in the coloured order at 1 thread; and the coloured parallel solve's physics against
// closed forms: a pile settles without sinking, stacks stand, head-on collisions keep momentum
// and give the restitution's relative speed. The scenes are large enough that colours of at
// least 128 constraints (world_parallel.cpp's kMinParallelItems) run split over the threads.
// Also the parallel forms of the restitution sweeps' looks (contact_restitution.cpp, with 512
// touching pairs and more) and of the broadphase's sweep (broadphase.cpp): a bouncing pile gives
// the same bytes at every thread count, and Newton's cradles and bouncing balls through them
// match the closed forms (the far sphere leaves with the striker's speed, a ball bounces to e² h).

#include "physics_test_support.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <vector>

namespace substep {
namespace {

WorldSettings settingsFor(int threads, bool sleeping = false) {
    return {.gravity = Vec3(0, -10, 0), .substeps = 10, .sleeping = sleeping, .threads = threads,
            .colouredSolve = true};
}

void addFloorAndWalls(World& world, double half) {
    world.createBody({.shape = planeShape(Vec3::UnitY(), 0.0), .type = BodyType::Static});
    for (int side = 0; side < 4; ++side) {
        const double x = side == 0 ? -half : side == 1 ? half : 0.0;
        const double z = side == 2 ? -half : side == 3 ? half : 0.0;
        const Vec3 size = side < 2 ? Vec3(0.2, 3.0, 2 * half + 0.2) : Vec3(2 * half + 0.2, 3.0, 0.2);
        world.createBody({.shape = boxShape(size), .type = BodyType::Static, .position = Vec3(x, 1.5, z)});
    }
}

/// 343 spheres (radius 5 cm, masses 0.1 to 0.4 kg) and boxes dropped in a 7 x 7 column into a
/// walled pit, the layers touching.
World pile(const WorldSettings& settings) {
    World world(settings);
    addFloorAndWalls(world, 0.5);
    for (int i = 0; i < 343; ++i) {
        const Vec3 position(-0.3 + 0.1 * (i % 7) + 0.002 * (i % 3), 0.06 + 0.1 * (i / 49),
                            -0.3 + 0.1 * ((i / 7) % 7));
        const Shape shape = i % 5 == 4 ? boxShape(Vec3(0.08, 0.07, 0.09)) : sphereShape(0.05);
        world.createBody({.shape = shape, .mass = 0.1 + 0.05 * (i % 7), .position = position,
                          .restitution = 0.1 * (i % 3)});
    }
    return world;
}

/// 36 stacks of 8 boxes of 20 cm, 1 kg, 1 mm apart, on the ground.
World stacks(const WorldSettings& settings) {
    World world(settings);
    world.createBody({.shape = planeShape(Vec3::UnitY(), 0.0), .type = BodyType::Static});
    for (int stack = 0; stack < 36; ++stack)
        for (int level = 0; level < 8; ++level)
            world.createBody({.shape = boxShape(Vec3(0.2, 0.2, 0.2)), .mass = 1.0,
                              .position = Vec3(0.3 * (stack % 6), 0.1 + 0.201 * level, 0.3 * (stack / 6))});
    return world;
}

/// 24 chains of 12 boxes joined by ball joints (two colours of 144 joints), hung from the world
/// at one end and let fall across one another onto a row of spheres lying on the ground.
World chains(const WorldSettings& settings) {
    World world(settings);
    world.createBody({.shape = planeShape(Vec3::UnitY(), 0.0), .type = BodyType::Static});
    for (int i = 0; i < 24; ++i)
        world.createBody({.shape = sphereShape(0.1), .mass = 0.5, .position = Vec3(0.15 * i - 1.8, 0.1, 0.3)});
    for (int chain = 0; chain < 24; ++chain) {
        BodyId previous;  // null: the world
        const Vec3 top(-1.2 + 0.1 * chain, 0.9, 0.05 * chain);
        for (int link = 0; link < 12; ++link) {
            const BodyId body = world.createBody({.shape = boxShape(Vec3(0.1, 0.04, 0.04)), .mass = 0.2,
                                                  .position = top + Vec3(0.1 * link + 0.05, 0.0, 0.0)});
            world.createJoint({.type = JointType::Spherical,
                               .body0 = previous,
                               .body1 = body,
                               .anchor0 = previous.isNull() ? top : Vec3(0.05, 0.0, 0.0),
                               .anchor1 = Vec3(-0.05, 0.0, 0.0)});
            previous = body;
        }
    }
    return world;
}

/// Steps the scene at 1 thread in the coloured order and at 2, 3 and 4 threads for `frames`,
/// and expects the same bytes after every frame.
template <class Build>
void expectSameBytesForEveryThreadCount(const Build& build, int frames, bool sleeping, const char* what) {
    std::vector<World> worlds;
    for (const int threads : {1, 2, 3, 4}) worlds.push_back(build(settingsFor(threads, sleeping)));
    for (int frame = 0; frame < frames; ++frame) {
        for (World& world : worlds) world.step(test::kDt);
        for (size_t k = 1; k < worlds.size(); ++k)
            ASSERT_EQ(test::differingBodies(worlds[0], worlds[k]), 0)
                << what << ": " << k + 1 << " threads differ from the coloured order at 1 thread at frame " << frame;
    }
    ASSERT_TRUE(worlds[0].isFinite()) << what;
    EXPECT_GT(worlds[0].activeContactCount() + worlds[0].sleepingBodyCount(), 60) << what << ": the scene must touch";
}

TEST(ParallelStepTest, PileSameBytesForEveryThreadCount) {
    expectSameBytesForEveryThreadCount(pile, 90, false, "pile");
    expectSameBytesForEveryThreadCount(pile, 150, true, "pile, sleeping");
}

TEST(ParallelStepTest, StacksSameBytesForEveryThreadCount) {
    expectSameBytesForEveryThreadCount(stacks, 60, false, "stacks");
}

TEST(ParallelStepTest, ChainsWithContactsSameBytesForEveryThreadCount) {
    expectSameBytesForEveryThreadCount(chains, 90, false, "chains");
}

TEST(ParallelStepTest, OneThreadWithoutColouringKeepsTheSerialOrder) {
    // The coloured order is another Gauss-Seidel order: at 1 thread, without colouredSolve, the
    // step is the serial one, which the coloured one does not reproduce bit for bit.
    WorldSettings serialSettings = settingsFor(1);
    serialSettings.colouredSolve = false;
    World serial = pile(serialSettings);
    World coloured = pile(settingsFor(1));
    for (int frame = 0; frame < 30; ++frame) {
        serial.step(test::kDt);
        coloured.step(test::kDt);
    }
    EXPECT_GT(test::differingBodies(serial, coloured), 0);
}

TEST(ParallelStepTest, PileSettlesWithoutSinkingAtTwoThreads) {
    World world = pile({.gravity = Vec3(0, -10, 0), .substeps = 20, .threads = 2});
    double deepest = 0.0;
    // Read at 4 s: a pile's last slides come when its arrangement says (the file comment of
    // tests/physics/sphere_piles.h); since the restitution sweeps' frictionless-pile fix one
    // passes at 3 s here (rms 0.0226 m/s at 3.0 s, 0.0095 at 2.5 s and 0.0102 at 3.5 s; before
    // it 0.0170 at 3 s and 0.0254 at 6 s, after a frame that gained 0.06 J at 5.5 s).
    test::runFor(world, 4.0, [&](double t) {
        if (t > 3.0) deepest = std::max(deepest, world.maxPenetration());
    });
    ASSERT_TRUE(world.isFinite());
    double squaredSpeeds = 0.0;
    double highest = 0.0;
    int moving = 0;
    for (const Body& b : world.bodies()) {
        if (b.invMass == 0.0) continue;
        squaredSpeeds += b.v.squaredNorm();
        highest = std::max(highest, b.x.y());
        ++moving;
    }
    const double rmsSpeed = std::sqrt(squaredSpeeds / moving);
    std::printf("pile at 4 s: deepest %.3g m, rms speed %.3g m/s, highest %.3g m\n", deepest, rmsSpeed, highest);
    EXPECT_LT(deepest, 1e-3) << "penetration over the last second (m)";
    // Dropped from up to 0.6 m (3.5 m/s at the floor), the pile comes to rest: what is left is
    // the slow creep of spheres rolling into the gaps.
    EXPECT_LT(rmsSpeed, 0.02) << "m/s";
    // Seven layers of 10 cm settle no higher than they were built, and stay in the pit.
    EXPECT_LT(highest, 0.72);
    EXPECT_GT(world.activeContactCount(), 600);
}

TEST(ParallelStepTest, StacksStandAtTwoThreads) {
    World world = stacks({.gravity = Vec3(0, -10, 0), .substeps = 20, .threads = 2});
    test::runFor(world, 3.0, [](double) {});
    ASSERT_TRUE(world.isFinite());
    // Every top box within 5 mm sideways of where it was put, and 8 box heights up (less the
    // gaps, closed, and the resting contacts' g h² sink).
    for (int stack = 0; stack < 36; ++stack) {
        const Body& top = world.bodies()[2 + stack * 8 + 7];  // 0: the world, 1: the ground
        const Vec3 start(0.3 * (stack % 6), 0.1 + 0.2 * 7, 0.3 * (stack / 6));
        EXPECT_LT(std::hypot(top.x.x() - start.x(), top.x.z() - start.z()), 5e-3) << "stack " << stack;
        EXPECT_NEAR(top.x.y(), start.y(), 2e-3) << "stack " << stack;
    }
}

TEST(ParallelStepTest, HeadOnCollisionsKeepMomentumAndRestitution) {
    // 160 pairs of spheres in zero gravity, each pair's spheres approaching head on at different
    // speeds and mass ratios: the colour holding them runs in parallel chunks. Closed form:
    // v0' = ((m0 − e m1) v0 + (1 + e) m1 v1) / (m0 + m1), and m0 v0 + m1 v1 kept.
    for (const double e : {0.0, 0.5, 1.0}) {
        World world({.gravity = Vec3::Zero(), .substeps = 20, .threads = 2});
        struct Pair {
            BodyId a, b;
            double ma, mb, va, vb;
        };
        std::vector<Pair> pairs;
        for (int i = 0; i < 160; ++i) {
            const double ma = 0.5 + 0.1 * (i % 7), mb = 0.3 + 0.2 * (i % 5);
            const double va = 1.0 + 0.01 * i, vb = -0.5 - 0.03 * (i % 11);
            const Vec3 at(0.0, 0.0, 0.5 * i);
            // Every pair meets at t = 0.05 s, so all of them touch in the same substeps.
            const double half = 0.1 + 0.5 * 0.05 * (va - vb);
            const BodyId a = world.createBody({.shape = sphereShape(0.1), .mass = ma, .position = at - Vec3(half, 0, 0),
                                               .velocity = Vec3(va, 0, 0), .restitution = e});
            const BodyId b = world.createBody({.shape = sphereShape(0.1), .mass = mb, .position = at + Vec3(half, 0, 0),
                                               .velocity = Vec3(vb, 0, 0), .restitution = e});
            pairs.push_back({a, b, ma, mb, va, vb});
        }
        test::runFor(world, 0.5, [](double) {});
        for (const Pair& p : pairs) {
            const double momentum = p.ma * p.va + p.mb * p.vb;
            const double va = world.body(p.a).v.x(), vb = world.body(p.b).v.x();
            const double scale = std::abs(p.ma * p.va) + std::abs(p.mb * p.vb);  // rounding is relative to it
            EXPECT_NEAR(p.ma * va + p.mb * vb, momentum, 1e-12 * scale) << "e " << e;
            const double expectedA = ((p.ma - e * p.mb) * p.va + (1 + e) * p.mb * p.vb) / (p.ma + p.mb);
            EXPECT_NEAR(va, expectedA, 1e-6) << "e " << e << ", masses " << p.ma << " and " << p.mb;
            EXPECT_LE(world.body(p.a).x.x(), world.body(p.b).x.x() - 0.2 + 1e-9) << "apart, not through";
        }
    }
}

/// 640 spheres (radius 5 cm, 0.1 to 0.4 kg, restitution 0.5 to 0.7) in ten layers 5 cm apart
/// dropped into a walled pit: layer after layer strikes the one below and bounces, so the
/// restitution sweeps open through the fall over more than 512 touching pairs.
World bouncingPile(const WorldSettings& settings) {
    World world(settings);
    addFloorAndWalls(world, 0.55);
    for (int i = 0; i < 640; ++i) {
        const Vec3 position(-0.385 + 0.11 * (i % 8) + 0.003 * (i % 3), 0.3 + 0.15 * (i / 64),
                            -0.385 + 0.11 * ((i / 8) % 8));
        world.createBody({.shape = sphereShape(0.05), .mass = 0.1 + 0.05 * (i % 7), .position = position,
                          .restitution = 0.5 + 0.1 * (i % 3)});
    }
    return world;
}

TEST(ParallelStepTest, BouncingPileSameBytesForEveryThreadCount) {
    expectSameBytesForEveryThreadCount(bouncingPile, 75, false, "bouncing pile");
    // The sweeps acted: under the paper's rule alone (Eq. 34) the same pile goes otherwise.
    WorldSettings paper = settingsFor(2);
    paper.sweptRestitution = false;
    World swept = bouncingPile(settingsFor(2));
    World paperRule = bouncingPile(paper);
    size_t mostContacts = 0;
    for (int frame = 0; frame < 45; ++frame) {
        swept.step(test::kDt);
        paperRule.step(test::kDt);
        mostContacts = std::max(mostContacts, swept.contacts().size());
    }
    EXPECT_GT(test::differingBodies(swept, paperRule), 100);
    EXPECT_GE(mostContacts, 512u) << "the sweeps' looks must run in blocks";
}

TEST(ParallelStepTest, NewtonsCradlesPassTheStrikersSpeedToTheFarSphere) {
    // 150 cradles in zero gravity, each a striker at 1 m/s into five touching equal spheres
    // (600 touching pairs: the sweeps' looks run in blocks, their colours split over the
    // threads). The closed form of elastic collisions handed down the row: everything stops
    // but the far sphere, which leaves at 1 m/s. The same bytes at 1 (coloured), 2 and 3 threads.
    constexpr int kCradles = 150;
    constexpr double kRadius = 0.1;
    const auto build = [&](int threads) {
        World world({.gravity = Vec3::Zero(), .substeps = 20, .threads = threads, .colouredSolve = true});
        for (int cradle = 0; cradle < kCradles; ++cradle) {
            const double z = 0.5 * cradle;
            const double mass = 0.3 + 0.1 * (cradle % 9);  // equal within a cradle
            for (int k = 0; k < 6; ++k) {
                const double x = k == 0 ? 0.0 : 2 * kRadius + 0.05 + (k - 1) * 2 * kRadius;
                world.createBody({.shape = sphereShape(kRadius), .mass = mass, .position = Vec3(x, 0, z),
                                  .velocity = k == 0 ? Vec3(1.0, 0, 0) : Vec3::Zero(), .staticFriction = 0.0,
                                  .dynamicFriction = 0.0, .restitution = 1.0});
            }
        }
        return world;
    };
    World one = build(1), two = build(2), three = build(3);
    size_t mostContacts = 0;
    for (int frame = 0; frame < 60; ++frame) {
        for (World* world : {&one, &two, &three}) world->step(test::kDt);
        mostContacts = std::max(mostContacts, two.contacts().size());
        ASSERT_EQ(test::differingBodies(one, two), 0) << "frame " << frame;
        ASSERT_EQ(test::differingBodies(one, three), 0) << "frame " << frame;
    }
    EXPECT_GE(mostContacts, 600u);
    for (int cradle = 0; cradle < kCradles; ++cradle)
        for (int k = 0; k < 6; ++k) {
            const Body& sphere = two.bodies()[static_cast<size_t>(1 + 6 * cradle + k)];  // 0: the world
            EXPECT_NEAR(sphere.v.x(), k == 5 ? 1.0 : 0.0, 2e-3) << "cradle " << cradle << ", sphere " << k;
        }
}

TEST(ParallelStepTest, BallsBounceToRestitutionSquaredTimesTheirDropAtTwoThreads) {
    // 1728 balls dropped 0.9 m onto the ground side by side (1728 touching pairs at the impact,
    // one colour: the sweeps' looks and the solve run in blocks), restitution 0.3, 0.6 or 0.9 and
    // masses 0.2 to 40 kg: each first bounce rises to e² times the drop, as one ball alone does.
    World world({.gravity = Vec3(0, -9.81, 0), .substeps = 20, .threads = 2});
    constexpr double kDrop = 0.9;
    constexpr int kBalls = 1728;
    const double restitutions[] = {0.3, 0.6, 0.9};
    const double masses[] = {0.2, 2.5, 40.0};
    // The ground's restitution is the ball's, so the pair's average is e: one ground per e,
    // meeting only its own balls (collision groups).
    for (uint32_t k = 0; k < 3; ++k)
        world.createBody({.shape = planeShape(Vec3::UnitY(), 0.0), .type = BodyType::Static,
                          .restitution = restitutions[k], .collisionGroup = 1u << k, .collisionMask = 1u << k});
    std::vector<BodyId> balls;
    for (int i = 0; i < kBalls; ++i)
        balls.push_back(world.createBody({.shape = sphereShape(0.1), .mass = masses[(i / 3) % 3],
                                          .position = Vec3(0.3 * (i % 24), 0.1 + kDrop, 0.3 * (i / 24)),
                                          .restitution = restitutions[i % 3], .collisionGroup = 1u << (i % 3),
                                          .collisionMask = 1u << (i % 3)}));
    std::vector<double> apex(kBalls, 0.0);
    std::vector<bool> bounced(kBalls, false);
    size_t mostContacts = 0;
    test::runFor(world, 0.43 * 1.9 + 0.05, [&](double) {
        mostContacts = std::max(mostContacts, world.contacts().size());
        for (int i = 0; i < kBalls; ++i) {
            const Body& b = world.body(balls[static_cast<size_t>(i)]);
            if (b.v.y() > 0.0) bounced[static_cast<size_t>(i)] = true;
            if (bounced[static_cast<size_t>(i)]) apex[static_cast<size_t>(i)] = std::max(apex[static_cast<size_t>(i)], b.x.y() - 0.1);
        }
    });
    EXPECT_GE(mostContacts, 512u) << "at the end of a frame";
    for (int i = 0; i < kBalls; ++i) {
        const double e = restitutions[i % 3];
        ASSERT_TRUE(bounced[static_cast<size_t>(i)]) << "ball " << i;
        EXPECT_NEAR(apex[static_cast<size_t>(i)], e * e * kDrop, 0.03 * e * e * kDrop + 2e-3) << "ball " << i << ", e " << e;
    }
}

}  // namespace
}  // namespace substep
