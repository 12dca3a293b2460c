// Tests engine/physics/collision/broadphase.cpp, with aabb_tree.cpp and shape_bounds.cpp under it:
// shape bounds against closed forms and corner enumeration, the tree against brute-force queries,
// and the broadphase's pairs against an O(n²) brute force over the same grown boxes
// (broadphase_reference.h); with a worker pool, the same pairs in the same order.

#include "physics/collision/broadphase.h"

#include "broadphase_reference.h"

#include "physics/collision/aabb_tree.h"
#include "physics/collision/shape_bounds.h"
#include "physics/world.h"
#include "physics/worker_pool.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <span>
#include <vector>

namespace substep {
namespace {

using namespace test_broadphase;

constexpr double kPi = 3.14159265358979323846;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void expectBox(const Aabb& box, const Vec3& min, const Vec3& max, double tolerance = 1e-12) {
    for (int a = 0; a < 3; ++a) {
        EXPECT_NEAR(box.min[a], min[a], tolerance) << "axis " << a;
        EXPECT_NEAR(box.max[a], max[a], tolerance) << "axis " << a;
    }
}

// --- Shape bounds ----------------------------------------------------------------------------

TEST(ShapeBoundsTest, SphereIgnoresRotation) {
    const Quat turned(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()));
    expectBox(shapeBounds(sphereShape(0.5), Vec3(1, 2, 3), turned), Vec3(0.5, 1.5, 2.5),
              Vec3(1.5, 2.5, 3.5));
}

TEST(ShapeBoundsTest, BoxTurnedAboutZMatchesClosedForm) {
    // Half extents (a, b, c) turned by θ about z: (a|cos θ| + b|sin θ|, a|sin θ| + b|cos θ|, c).
    const double a = 0.5, b = 0.2, c = 0.3;
    for (const double theta : {0.0, 0.3, kPi / 4, 1.2, kPi / 2, 2.5, -0.8}) {
        const Quat q(Eigen::AngleAxisd(theta, Vec3::UnitZ()));
        const Vec3 half(a * std::abs(std::cos(theta)) + b * std::abs(std::sin(theta)),
                        a * std::abs(std::sin(theta)) + b * std::abs(std::cos(theta)), c);
        const Vec3 p(1, -2, 0.5);
        expectBox(shapeBounds(boxShape(Vec3(2 * a, 2 * b, 2 * c)), p, q), p - half, p + half);
    }
}

TEST(ShapeBoundsTest, BoxMatchesItsCornersForRandomOrientations) {
    // A box's extreme points are corners: the tight box is the box of the 8 turned corners.
    std::mt19937 rng(7);
    const Vec3 size(0.4, 1.0, 0.1);
    for (int trial = 0; trial < 100; ++trial) {
        const Quat q = randomOrientation(rng);
        const Vec3 p(0.3 * trial, -1.0, 2.0);
        Aabb corners;
        for (int i = 0; i < 8; ++i) {
            const Vec3 local(i & 1 ? 0.2 : -0.2, i & 2 ? 0.5 : -0.5, i & 4 ? 0.05 : -0.05);
            corners.grow(p + q * local);
        }
        expectBox(shapeBounds(boxShape(size), p, q), corners.min, corners.max);
    }
}

TEST(ShapeBoundsTest, CapsuleTurnedAboutZMatchesClosedForm) {
    // Segment of length L along local y turned by θ about z: half extents
    // (L/2 |sin θ| + r, L/2 |cos θ| + r, r).
    const double r = 0.1, length = 0.6;
    for (const double theta : {0.0, 0.4, kPi / 2, 2.0, -1.0}) {
        const Quat q(Eigen::AngleAxisd(theta, Vec3::UnitZ()));
        const Vec3 half(0.5 * length * std::abs(std::sin(theta)) + r,
                        0.5 * length * std::abs(std::cos(theta)) + r, r);
        expectBox(shapeBounds(capsuleShape(r, length), Vec3::Zero(), q), -half, half);
    }
}

TEST(ShapeBoundsTest, CapsuleMatchesItsSegmentEndsForRandomOrientations) {
    // Along each axis the capsule reaches r beyond the farther end of its segment.
    std::mt19937 rng(11);
    const double r = 0.25, length = 1.5;
    for (int trial = 0; trial < 100; ++trial) {
        const Quat q = randomOrientation(rng);
        const Vec3 p(-1.0, 0.1 * trial, 3.0);
        const Vec3 end0 = p + q * Vec3(0, 0.5 * length, 0);
        const Vec3 end1 = p - q * Vec3(0, 0.5 * length, 0);
        const Vec3 min = end0.cwiseMin(end1) - Vec3::Constant(r);
        const Vec3 max = end0.cwiseMax(end1) + Vec3::Constant(r);
        expectBox(shapeBounds(capsuleShape(r, length), p, q), min, max);
    }
}

TEST(ShapeBoundsTest, MeshTurnsItsLocalBounds) {
    Shape mesh{.type = ShapeType::Mesh};
    mesh.localBounds = {Vec3(0, 0, 0), Vec3(1, 2, 3)};
    // 90° about y: local x -> world -z, local z -> world x.
    const Quat q(Eigen::AngleAxisd(kPi / 2, Vec3::UnitY()));
    expectBox(shapeBounds(mesh, Vec3(10, 0, 0), q), Vec3(10, 0, -1), Vec3(13, 2, 0));
}

TEST(ShapeBoundsTest, MeshWithoutLocalBoundsUsesItsVertices) {
    auto triangles = std::make_shared<TriangleMesh>();
    triangles->vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 2, 0), Vec3(0, 0, -3)};
    Shape mesh{.type = ShapeType::Mesh, .mesh = triangles};
    expectBox(shapeBounds(mesh, Vec3(1, 1, 1), Quat::Identity()), Vec3(1, 1, -2), Vec3(2, 3, 1));
}

TEST(ShapeBoundsTest, DegenerateShapes) {
    EXPECT_TRUE(shapeBounds(Shape{}, Vec3::Zero(), Quat::Identity()).isEmpty());
    const Aabb plane = shapeBounds(planeShape(Vec3::UnitY(), 0.0), Vec3::Zero(), Quat::Identity());
    EXPECT_EQ(plane.min.x(), -kInf);
    EXPECT_EQ(plane.max.y(), kInf);
    // Zero sizes give a point, not an empty box.
    const Vec3 p(1, 2, 3);
    expectBox(shapeBounds(boxShape(Vec3::Zero()), p, Quat::Identity()), p, p);
    expectBox(shapeBounds(sphereShape(0.0), p, Quat::Identity()), p, p);
    expectBox(shapeBounds(capsuleShape(0.0, 0.0), p, Quat::Identity()), p, p);
    // A heightfield whose builder left no bounds has nothing to box.
    EXPECT_TRUE(shapeBounds(Shape{.type = ShapeType::Heightfield}, p, Quat::Identity()).isEmpty());
}

TEST(ShapeBoundsTest, ReachIsTheFarthestPointFromTheOrigin) {
    EXPECT_DOUBLE_EQ(shapeReach(sphereShape(0.3)), 0.3);
    EXPECT_DOUBLE_EQ(shapeReach(capsuleShape(0.1, 1.0)), 0.6);
    EXPECT_DOUBLE_EQ(shapeReach(boxShape(Vec3(2, 4, 4))), 3.0);  // half diagonal √(1+4+4)
    EXPECT_DOUBLE_EQ(shapeReach(Shape{}), 0.0);
}

// --- AABB tree -------------------------------------------------------------------------------

Aabb randomBox(std::mt19937& rng, double extent, double maxSize) {
    std::uniform_real_distribution<double> position(-extent, extent);
    std::uniform_real_distribution<double> size(0.0, maxSize);
    const Vec3 min(position(rng), position(rng), position(rng));
    return {min, min + Vec3(size(rng), size(rng), size(rng))};
}

std::set<uint32_t> treeQuery(const AabbTree& tree, const Aabb& box) {
    std::set<uint32_t> hits;
    tree.query(box, [&](int32_t proxy) { hits.insert(tree.userData(proxy)); });
    return hits;
}

TEST(AabbTreeTest, QueriesMatchBruteForceThroughInsertMoveAndRemove) {
    std::mt19937 rng(3);
    AabbTree tree(0.1);
    std::vector<int32_t> proxies;
    std::vector<Aabb> boxes;
    for (uint32_t i = 0; i < 400; ++i) {
        boxes.push_back(randomBox(rng, 10.0, 1.0));
        proxies.push_back(tree.createProxy(boxes.back(), i));
    }
    std::vector<bool> present(boxes.size(), true);
    auto check = [&] {
        ASSERT_STREQ(tree.validate(), "");
        for (int q = 0; q < 50; ++q) {
            const Aabb query = randomBox(rng, 10.0, 3.0);
            std::set<uint32_t> expected;
            for (uint32_t i = 0; i < boxes.size(); ++i) {
                if (present[i]) {
                    // Every leaf keeps a fat box containing the box it was last given.
                    ASSERT_TRUE(tree.fatBox(proxies[i]).contains(boxes[i]));
                    if (tree.fatBox(proxies[i]).overlaps(query)) expected.insert(i);
                }
            }
            ASSERT_EQ(treeQuery(tree, query), expected);
        }
    };
    check();

    // Small moves stay inside the fat boxes, large ones re-insert.
    std::uniform_real_distribution<double> jitter(-0.5, 0.5);
    for (int round = 0; round < 5; ++round) {
        for (uint32_t i = 0; i < boxes.size(); ++i) {
            const Vec3 shift(jitter(rng), jitter(rng), jitter(rng));
            boxes[i] = {boxes[i].min + shift, boxes[i].max + shift};
            tree.moveProxy(proxies[i], boxes[i]);
        }
        check();
    }

    for (uint32_t i = 0; i < boxes.size(); i += 2) {
        tree.destroyProxy(proxies[i]);
        present[i] = false;
    }
    EXPECT_EQ(tree.proxyCount(), 200);
    check();
}

TEST(AabbTreeTest, MoveInsideTheFatBoxLeavesTheTreeAlone) {
    AabbTree tree(0.1);
    const int32_t proxy = tree.createProxy({Vec3::Zero(), Vec3::Ones()}, 0);
    tree.createProxy({Vec3(5, 5, 5), Vec3(6, 6, 6)}, 1);
    EXPECT_FALSE(tree.moveProxy(proxy, {Vec3::Constant(0.05), Vec3::Constant(1.05)}));
    EXPECT_TRUE(tree.moveProxy(proxy, {Vec3::Constant(0.5), Vec3::Constant(1.5)}));
    EXPECT_STREQ(tree.validate(), "");
}

TEST(AabbTreeTest, StaysShallowForSortedInsertion) {
    // Boxes arriving in order along a line are the worst case of an unbalanced tree (height n).
    AabbTree tree(0.0);
    const int count = 1024;
    for (int i = 0; i < count; ++i) {
        tree.createProxy({Vec3(i, 0, 0), Vec3(i + 0.5, 1, 1)}, static_cast<uint32_t>(i));
    }
    EXPECT_STREQ(tree.validate(), "");
    EXPECT_LE(tree.height(), 2 * 10);  // twice log2(count)
}

TEST(AabbTreeTest, ReusesFreedNodes) {
    AabbTree tree;
    std::vector<int32_t> proxies;
    for (uint32_t i = 0; i < 10; ++i)
        proxies.push_back(tree.createProxy({Vec3::Zero(), Vec3::Ones()}, i));
    for (const int32_t p : proxies)
        tree.destroyProxy(p);
    EXPECT_EQ(tree.height(), -1);
    EXPECT_STREQ(tree.validate(), "");
    for (uint32_t i = 0; i < 10; ++i)
        EXPECT_LT(tree.createProxy({Vec3::Zero(), Vec3::Ones()}, i), 19);
    EXPECT_STREQ(tree.validate(), "");
}

TEST(BroadphaseParallelTest, APoolGivesTheSamePairsInTheSameOrder) {
    // The sweep's overlap tests in blocks on 2 and 3 threads (broadphase.cpp): the pairs of the
    // serial update, frame after frame, with more boxes than the parallel sweep's threshold.
    std::mt19937 rng(11);
    std::vector<Body> bodies = randomScene(rng, 1200);
    uint32_t nextGeneration = 100000;
    WorkerPool two(2), three(3);
    Broadphase serial, onTwo, onThree;
    for (int frame = 0; frame < 20; ++frame) {
        serial.update(bodies, kDt);
        onTwo.update(bodies, kDt, 2.0, nullptr, &two);
        onThree.update(bodies, kDt, 2.0, nullptr, &three);
        ASSERT_GT(serial.pairs().size(), 300u);
        ASSERT_EQ(toVector(onTwo.pairs()), toVector(serial.pairs())) << "frame " << frame;
        ASSERT_EQ(toVector(onThree.pairs()), toVector(serial.pairs())) << "frame " << frame;
        advance(rng, bodies, nextGeneration);
    }
}

// --- Broadphase: against the brute-force reference (broadphase_reference.h) -------------------

class BroadphaseMethodTest : public ::testing::TestWithParam<BroadphaseMethod> {};

TEST_P(BroadphaseMethodTest, RandomScenesMatchBruteForceFrameAfterFrame) {
    for (const unsigned seed : {1u, 2u, 3u}) {
        std::mt19937 rng(seed);
        std::vector<Body> bodies = randomScene(rng, 300);
        uint32_t nextGeneration = 100000;
        const BroadphaseSettings settings{.method = GetParam()};
        Broadphase broadphase(settings);
        for (int frame = 0; frame < 40; ++frame) {
            broadphase.update(bodies, kDt);
            const std::vector<BodyPair> expected = bruteForcePairs(bodies, kDt, 2.0, settings);
            ASSERT_EQ(toVector(broadphase.pairs()), expected)
                << "seed " << seed << " frame " << frame;
            if (frame == 0) {
                // The scene exercises every kind of pair: plane, static, dynamic.
                const auto hasPair = [&](auto&& test) {
                    return std::any_of(expected.begin(), expected.end(), test);
                };
                ASSERT_GT(expected.size(), 100u);
                ASSERT_TRUE(hasPair([](const BodyPair& p) { return p.body0 == 1; }));
                ASSERT_TRUE(hasPair([](const BodyPair& p) { return p.body0 == 2; }));
                ASSERT_TRUE(hasPair([&](const BodyPair& p) {
                    return !bodies[p.body0].isDynamic() && p.body0 > 2;
                }));
                ASSERT_TRUE(hasPair([&](const BodyPair& p) {
                    return bodies[p.body1].shape.type == ShapeType::Mesh;
                }));
            }
            advance(rng, bodies, nextGeneration);
        }
    }
}

TEST_P(BroadphaseMethodTest, OtherSafetyFactorsAndTimeSteps) {
    std::mt19937 rng(5);
    const std::vector<Body> bodies = randomScene(rng, 200);
    const BroadphaseSettings settings{.method = GetParam(), .margin = 0.0};
    Broadphase broadphase(settings);
    for (const double k : {1.0, 2.0, 4.0}) {
        for (const double dt : {1.0 / 240.0, 1.0 / 30.0}) {
            broadphase.update(bodies, dt, k);
            EXPECT_EQ(toVector(broadphase.pairs()), bruteForcePairs(bodies, dt, k, settings));
        }
    }
}

TEST_P(BroadphaseMethodTest, SweptGrowthMatchesBruteForce) {
    std::mt19937 rng(4);
    std::vector<Body> bodies = randomScene(rng, 300);
    uint32_t nextGeneration = 100000;
    const BroadphaseSettings settings{.method = GetParam(), .sweptGrowth = true};
    Broadphase broadphase(settings);
    for (int frame = 0; frame < 20; ++frame) {
        broadphase.update(bodies, kDt);
        ASSERT_EQ(toVector(broadphase.pairs()), bruteForcePairs(bodies, kDt, 2.0, settings))
            << "frame " << frame;
        advance(rng, bodies, nextGeneration);
    }
}

TEST_P(BroadphaseMethodTest, ApproachingBodiesPairAndSeparatingOnesUnpair) {
    std::vector<Body> bodies(1);
    bodies.push_back(makeTestBody(sphereShape(0.1), Vec3(-1, 0, 0), false));
    bodies.push_back(makeTestBody(sphereShape(0.1), Vec3(1, 0, 0), false));
    bodies[1].v = Vec3(1, 0, 0);
    bodies[2].v = Vec3(-1, 0, 0);
    Broadphase broadphase({.method = GetParam()});
    bool paired = false;
    for (int frame = 0; frame < 120; ++frame) {
        broadphase.update(bodies, kDt);
        // Grown by 2·dt·|v| + margin each: paired once the gap is below twice that.
        const double gap = (bodies[2].x - bodies[1].x).norm() - 0.2;
        const double reach = 2.0 * (2.0 * kDt * 1.0 + broadphase.settings().margin);
        const bool expected = gap <= reach + 1e-12;
        ASSERT_EQ(broadphase.pairs().size(), expected ? 1u : 0u) << "frame " << frame;
        if (expected) {
            EXPECT_EQ(broadphase.pairs()[0], (BodyPair{1, 2}));
        }
        paired = paired || expected;
        for (size_t i = 1; i < 3; ++i)
            bodies[i].x += bodies[i].v * kDt;  // they pass through
    }
    EXPECT_TRUE(paired);
    EXPECT_TRUE(broadphase.pairs().empty());  // apart again at the end
}

INSTANTIATE_TEST_SUITE_P(Methods, BroadphaseMethodTest,
                         ::testing::Values(BroadphaseMethod::AabbTree,
                                           BroadphaseMethod::SweepAndPrune));

// --- Broadphase: rules ---------------------------------------------------------------------------

TEST(BroadphaseTest, StaticPairsAreNeverReported) {
    std::vector<Body> bodies(1);
    bodies.push_back(makeTestBody(boxShape(Vec3::Ones()), Vec3::Zero(), true));
    bodies.push_back(makeTestBody(boxShape(Vec3::Ones()), Vec3(0.5, 0, 0), true));
    bodies.push_back(makeTestBody(planeShape(Vec3::UnitY(), 0.0), Vec3::Zero(), true));
    Broadphase broadphase;
    broadphase.update(bodies, kDt);
    EXPECT_TRUE(broadphase.pairs().empty());
    EXPECT_EQ(broadphase.staticCount(), 2);  // planes stay out of the tree

    // A dynamic body overlapping both statics and the plane pairs with all three.
    bodies.push_back(makeTestBody(sphereShape(0.5), Vec3(0.2, 0, 0), false));
    broadphase.update(bodies, kDt);
    EXPECT_EQ(toVector(broadphase.pairs()), (std::vector<BodyPair>{{1, 4}, {2, 4}, {3, 4}}));
}

TEST(BroadphaseTest, BodiesThatDoNotCollideAreLeftOut) {
    std::vector<Body> bodies(1);
    bodies[0].alive = true;   // the anchor: ShapeType::None
    bodies[0].invMass = 1.0;  // even if it were dynamic
    bodies.push_back(makeTestBody(sphereShape(0.5), Vec3::Zero(), false));
    bodies.push_back(makeTestBody(sphereShape(0.5), Vec3(0.1, 0, 0), false));
    bodies.push_back(makeTestBody(sphereShape(0.5), Vec3(0.2, 0, 0), false));
    bodies[2].collide = false;
    Broadphase broadphase;
    broadphase.update(bodies, kDt);
    EXPECT_EQ(toVector(broadphase.pairs()), (std::vector<BodyPair>{{1, 3}}));
    EXPECT_TRUE(broadphase.bounds(2).isEmpty());

    bodies[2].collide = true;
    broadphase.update(bodies, kDt);
    EXPECT_EQ(toVector(broadphase.pairs()), (std::vector<BodyPair>{{1, 2}, {1, 3}, {2, 3}}));
}

TEST(BroadphaseTest, PlanesPairOnlyWithBodiesThatReachThem) {
    std::vector<Body> bodies(1);
    bodies.push_back(makeTestBody(planeShape(Vec3::UnitY(), 0.0), Vec3::Zero(), true));
    bodies.push_back(makeTestBody(sphereShape(0.1), Vec3(5, 0.5, 0), false));     // above, at rest
    bodies.push_back(makeTestBody(sphereShape(0.1), Vec3(-5, 0.102, 0), false));  // within margin
    bodies.push_back(makeTestBody(sphereShape(0.1), Vec3(0, -3, 0), false));      // sunk below
    bodies.push_back(makeTestBody(boxShape(Vec3::Ones()), Vec3(0, 0.2, 0), true));  // static
    bodies.push_back(makeTestBody(sphereShape(0.1), Vec3(9, 0.4, 0), false));       // falling fast
    bodies[6].v = Vec3(0, -10, 0);  // grown by 2·dt·10 = 0.33 m: reaches down to -0.035
    // A tilted plane x + y = 0 (normal not unit: the same half-space).
    bodies.push_back(makeTestBody(planeShape(Vec3(2, 2, 0), 0.0), Vec3::Zero(), true));
    Broadphase broadphase;
    broadphase.update(bodies, kDt);
    // Body 2 is far on the positive side of the tilted plane; 3 and 4 are beyond it.
    EXPECT_EQ(toVector(broadphase.pairs()),
              (std::vector<BodyPair>{{1, 3}, {1, 4}, {1, 6}, {3, 7}, {4, 7}}));
}

TEST(BroadphaseTest, DestroyedAndReusedSlotsLeaveTheirOldPairs) {
    World world;
    const BodyId a = world.createBody({.shape = sphereShape(0.5), .mass = 1.0});
    const BodyId b =
        world.createBody({.shape = sphereShape(0.5), .mass = 1.0, .position = Vec3(0.5, 0, 0)});
    const BodyId c = world.createBody(
        {.shape = boxShape(Vec3::Ones()), .type = BodyType::Static, .position = Vec3(-0.6, 0, 0)});
    Broadphase broadphase;
    broadphase.update(world.bodies(), kDt);
    EXPECT_EQ(toVector(broadphase.pairs()),
              (std::vector<BodyPair>{{a.index, b.index}, {a.index, c.index}}));
    EXPECT_EQ(broadphase.dynamicCount(), 2);
    EXPECT_EQ(broadphase.staticCount(), 1);

    world.destroyBody(a);
    world.destroyBody(c);
    broadphase.update(world.bodies(), kDt);
    EXPECT_TRUE(broadphase.pairs().empty());
    EXPECT_EQ(broadphase.dynamicCount(), 1);
    EXPECT_EQ(broadphase.staticCount(), 0);

    // New bodies take the freed slots elsewhere; nothing of the old ones remains.
    const BodyId d =
        world.createBody({.shape = sphereShape(0.1), .mass = 1.0, .position = Vec3(10, 0, 0)});
    const BodyId e = world.createBody(
        {.shape = sphereShape(0.1), .type = BodyType::Static, .position = Vec3(0.5, 0.55, 0)});
    EXPECT_EQ(d.index, c.index);  // the world hands out the last freed slot first
    EXPECT_EQ(e.index, a.index);
    broadphase.update(world.bodies(), kDt);
    EXPECT_EQ(toVector(broadphase.pairs()), (std::vector<BodyPair>{{e.index, b.index}}));
}

TEST(BroadphaseTest, PairsAreSortedAndRunsAreRepeatable) {
    std::mt19937 rngA(9), rngB(9);
    std::vector<Body> scene = randomScene(rngA, 400);
    std::vector<Body> copy = randomScene(rngB, 400);
    Broadphase tree({.method = BroadphaseMethod::AabbTree});
    Broadphase again({.method = BroadphaseMethod::AabbTree});
    Broadphase sweep({.method = BroadphaseMethod::SweepAndPrune});
    uint32_t generationA = 100000, generationB = 100000;
    for (int frame = 0; frame < 20; ++frame) {
        tree.update(scene, kDt);
        again.update(copy, kDt);
        sweep.update(scene, kDt);
        const auto pairs = tree.pairs();
        for (size_t i = 1; i < pairs.size(); ++i) {
            ASSERT_TRUE(
                pairs[i - 1].body0 < pairs[i].body0 ||
                (pairs[i - 1].body0 == pairs[i].body0 && pairs[i - 1].body1 < pairs[i].body1));
        }
        for (const BodyPair& p : pairs)
            ASSERT_LT(p.body0, p.body1);
        ASSERT_EQ(toVector(pairs), toVector(again.pairs()));
        ASSERT_EQ(toVector(pairs), toVector(sweep.pairs()));
        advance(rngA, scene, generationA);
        advance(rngB, copy, generationB);
    }
}

TEST(BroadphaseTest, StillStaticBodiesKeepTheirBoxes) {
    std::vector<Body> bodies(1);
    bodies.push_back(makeTestBody(boxShape(Vec3(4, 0.2, 4)), Vec3::Zero(), true));
    bodies.push_back(makeTestBody(sphereShape(0.1), Vec3(0, 0.3, 0), false));
    Broadphase broadphase;
    broadphase.update(bodies, kDt);
    EXPECT_TRUE(broadphase.pairs().empty());
    // Moved by hand, the static floor is re-boxed and meets the sphere.
    bodies[1].x.y() += 0.1;
    broadphase.update(bodies, kDt);
    EXPECT_EQ(toVector(broadphase.pairs()), (std::vector<BodyPair>{{1, 2}}));
    // Resized in place, too.
    bodies[1].x.y() -= 0.1;
    bodies[1].shape.size.y() = 0.4;
    broadphase.update(bodies, kDt);
    EXPECT_EQ(toVector(broadphase.pairs()), (std::vector<BodyPair>{{1, 2}}));
    bodies[1].shape.size.y() = 0.2;
    broadphase.update(bodies, kDt);
    EXPECT_TRUE(broadphase.pairs().empty());
}

TEST(BroadphaseTest, RotationGrowsTheBoxByTheReach) {
    // A long capsule spinning about z sweeps out to its tips: growth k·dt·|ω|·reach.
    std::vector<Body> bodies(1);
    bodies.push_back(makeTestBody(capsuleShape(0.05, 2.0), Vec3::Zero(), false));
    bodies[1].omega = Vec3(0, 0, 6.0);
    Broadphase broadphase({.margin = 0.0});
    broadphase.update(bodies, kDt);
    const double growth = 2.0 * kDt * 6.0 * 1.05;
    expectBox(broadphase.bounds(1), Vec3(-0.05 - growth, -1.05 - growth, -0.05 - growth),
              Vec3(0.05 + growth, 1.05 + growth, 0.05 + growth), 1e-9);
}

TEST(BroadphaseTest, SweptGrowthStretchesTheBoxAlongTheVelocity) {
    std::vector<Body> bodies(1);
    bodies.push_back(makeTestBody(sphereShape(0.1), Vec3(1, 2, 3), false));
    bodies[1].v = Vec3(6, 0, -3);
    Broadphase broadphase({.sweptGrowth = true});
    broadphase.update(bodies, kDt);
    const double m = broadphase.settings().margin;
    // k·dt·v = (0.2, 0, -0.1): the sphere's box at the start and at the end of the sweep.
    expectBox(broadphase.bounds(1), Vec3(0.9 - m, 1.9 - m, 2.8 - m),
              Vec3(1.3 + m, 2.1 + m, 3.1 + m), 1e-12);
    // A runaway velocity falls back to the clamped growth on every side.
    bodies[1].v = Vec3(kNaN, 0, 0);
    broadphase.update(bodies, kDt);
    EXPECT_NEAR(broadphase.bounds(1).extents().y(), 0.2 + 2 * (broadphase.settings().maxGrowth + m),
                1e-9);
}

TEST(BroadphaseTest, RunawayAndNonFiniteBodiesDoNotBreakIt) {
    std::vector<Body> bodies(1);
    for (int i = 0; i < 8; ++i) {
        bodies.push_back(makeTestBody(sphereShape(0.1), Vec3(0.15 * i, 0, 0), false));
    }
    bodies[1].v = Vec3(kInf, 0, 0);
    bodies[2].v = Vec3(kNaN, 0, 0);
    bodies[3].v = Vec3(1e300, 1e300, 0);
    bodies[4].omega = Vec3(0, kNaN, 0);
    bodies[5].x = Vec3(kNaN, 0, 0);  // a body whose state blew up
    bodies[6].q.coeffs() = Eigen::Vector4d(kInf, 0, 0, 0);
    bodies[7].x = Vec3(1e308, 1e308, 1e308);
    const BroadphaseSettings settings;
    for (const BroadphaseMethod method :
         {BroadphaseMethod::AabbTree, BroadphaseMethod::SweepAndPrune}) {
        Broadphase broadphase({.method = method});
        for (int frame = 0; frame < 3; ++frame) {
            broadphase.update(bodies, kDt);
            for (const uint32_t i : {1u, 2u, 3u, 4u}) {
                const Aabb& box = broadphase.bounds(i);
                ASSERT_TRUE(box.min.allFinite() && box.max.allFinite());
                // Clamped growth: the box is the sphere grown by maxGrowth + margin.
                EXPECT_NEAR(box.extents().x(), 0.2 + 2 * (settings.maxGrowth + settings.margin),
                            1e-9);
            }
            EXPECT_TRUE(broadphase.bounds(5).isEmpty());
            EXPECT_TRUE(broadphase.bounds(6).isEmpty());
            for (const BodyPair& p : broadphase.pairs()) {
                EXPECT_NE(p.body0, 5u);
                EXPECT_NE(p.body1, 5u);
                EXPECT_NE(p.body1, 6u);
            }
            // The runaway bodies still pair with everything they can reach.
            EXPECT_EQ(toVector(broadphase.pairs()), bruteForcePairs(bodies, kDt, 2.0, settings));
        }
        // Non-finite time steps too.
        broadphase.update(bodies, kNaN);
        broadphase.update(bodies, -kDt);
        broadphase.update(bodies, kInf, kInf);
    }
}

TEST(BroadphaseTest, ZeroSizedShapesAndAShrinkingWorld) {
    std::vector<Body> bodies(1);
    bodies.push_back(makeTestBody(boxShape(Vec3::Zero()), Vec3::Zero(), false));
    bodies.push_back(makeTestBody(sphereShape(0.0), Vec3(0.005, 0, 0), false));
    bodies.push_back(makeTestBody(capsuleShape(0.0, 0.0), Vec3(0.5, 0, 0), false));
    Broadphase broadphase;
    broadphase.update(bodies, kDt);
    // Points 5 mm apart, each box grown by the 5 mm margin.
    EXPECT_EQ(toVector(broadphase.pairs()), (std::vector<BodyPair>{{1, 2}}));
    bodies.resize(2);
    broadphase.update(bodies, kDt);
    EXPECT_TRUE(broadphase.pairs().empty());
    EXPECT_EQ(broadphase.dynamicCount(), 1);
    broadphase.update({}, kDt);
    EXPECT_TRUE(broadphase.pairs().empty());
}

}  // namespace
}  // namespace substep
