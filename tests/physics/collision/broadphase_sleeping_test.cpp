// Tests engine/physics/collision/broadphase.cpp's sleeping bodies (Broadphase::update's sleep
// flags): with bodies falling asleep and waking frame after frame, static bodies moved, planes
// changed and slots reused, the pairs are exactly the brute force's over the same boxes, by both
// methods; and a sleeping body's box and pairs are kept from the update it fell asleep in, not
// searched again.

#include "physics/collision/broadphase.h"

#include "broadphase_reference.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace substep {
namespace {

using namespace test_broadphase;

/// One frame of a running world with sleeping: advance() moves the scene and edits slots; a
/// sleeping body does not move, and any edit of it (destroyed, made static, collide toggled)
/// wakes it, as the world's edits do. Then about 10 % of the awake dynamic bodies fall asleep
/// (still, as the world leaves them) and 4 % of the sleeping ones wake at a new velocity.
void advanceWithSleep(std::mt19937& rng, std::vector<Body>& bodies, std::vector<uint8_t>& asleep,
                      uint32_t& nextGeneration) {
    const std::vector<Body> before = bodies;
    advance(rng, bodies, nextGeneration);
    for (size_t i = 0; i < bodies.size(); ++i) {
        if (!asleep[i]) continue;
        Body& body = bodies[i];
        const Body& was = before[i];
        const bool edited = body.alive != was.alive || body.generation != was.generation ||
                            body.collide != was.collide || body.invMass != was.invMass;
        if (edited) {
            asleep[i] = 0;
        } else {
            body.x = was.x;  // not integrated while asleep
            body.q = was.q;
        }
    }
    std::uniform_int_distribution<int> pick(0, 999);
    std::uniform_real_distribution<double> speed(-4.0, 4.0);
    for (size_t i = 3; i < bodies.size(); ++i) {
        Body& body = bodies[i];
        const int event = pick(rng);
        if (asleep[i]) {
            if (event < 40) {
                asleep[i] = 0;
                body.v = Vec3(speed(rng), speed(rng), speed(rng));
            }
        } else if (body.alive && body.isDynamic() && event < 100) {
            asleep[i] = 1;
            body.v.setZero();
            body.omega.setZero();
        }
    }
}

class BroadphaseSleepingTest : public ::testing::TestWithParam<BroadphaseMethod> {};

TEST_P(BroadphaseSleepingTest, SleepingAndWakingBodiesPairAsTheBruteForceSays) {
    for (const unsigned seed : {1u, 2u, 3u}) {
        std::mt19937 rng(seed);
        std::vector<Body> bodies = randomScene(rng, 300);
        std::vector<uint8_t> asleep(bodies.size(), 0);
        uint32_t nextGeneration = 100000;
        const BroadphaseSettings settings{.method = GetParam()};
        Broadphase broadphase(settings);
        int mostAsleep = 0;
        size_t sleepingPairs = 0;
        for (int frame = 0; frame < 80; ++frame) {
            // The ground plane rises and comes back: a changed plane meets sleeping bodies.
            if (frame == 30 || frame == 31) bodies[1].shape.offset += frame == 30 ? 0.5 : -0.5;
            broadphase.update(bodies, kDt, 2.0, asleep.data());
            const std::vector<BodyPair> expected = bruteForcePairs(bodies, kDt, 2.0, settings);
            ASSERT_EQ(toVector(broadphase.pairs()), expected)
                << "seed " << seed << " frame " << frame;
            mostAsleep = std::max(mostAsleep, broadphase.sleepingCount());
            for (const BodyPair& pair : expected)
                if (asleep[pair.body0] && asleep[pair.body1]) ++sleepingPairs;
            advanceWithSleep(rng, bodies, asleep, nextGeneration);
        }
        // The scenes exercised it: a third of the dynamic bodies asleep at times, many pairs kept.
        EXPECT_GT(mostAsleep, 80) << seed;
        EXPECT_GT(sleepingPairs, 500u) << seed;
    }
}

TEST_P(BroadphaseSleepingTest, WithoutFlagsEverySleepingBodyIsSearchedAgain) {
    // Sleeping turned off (null flags) after half the scene slept: the next update's pairs are
    // the brute force's, every body back in the sweep.
    std::mt19937 rng(7);
    std::vector<Body> bodies = randomScene(rng, 200);
    std::vector<uint8_t> asleep(bodies.size(), 0);
    for (size_t i = 3; i < bodies.size(); i += 2) {
        if (!bodies[i].isDynamic()) continue;
        asleep[i] = 1;
        bodies[i].v.setZero();
        bodies[i].omega.setZero();
    }
    const BroadphaseSettings settings{.method = GetParam()};
    Broadphase broadphase(settings);
    broadphase.update(bodies, kDt, 2.0, asleep.data());
    ASSERT_GT(broadphase.sleepingCount(), 50);
    for (size_t i = 3; i < bodies.size(); ++i)
        if (bodies[i].isDynamic()) bodies[i].v = Vec3(0.5, -1.0, 0.25);
    broadphase.update(bodies, kDt);
    EXPECT_EQ(broadphase.sleepingCount(), 0);
    EXPECT_EQ(toVector(broadphase.pairs()), bruteForcePairs(bodies, kDt, 2.0, settings));
}

INSTANTIATE_TEST_SUITE_P(Methods, BroadphaseSleepingTest,
                         ::testing::Values(BroadphaseMethod::SweepAndPrune,
                                           BroadphaseMethod::AabbTree));

TEST(BroadphaseSleepingRuleTest, ASleepingBodysBoxAndPairsAreKeptNotSearchedAgain) {
    // Two sleeping balls touching, and a third far off. Moved behind the broadphase's back (which
    // the world never does: its edits wake a body), the first ball keeps the box and the pair it
    // fell asleep with, and the far one stays unpaired: neither was looked at again.
    std::vector<Body> bodies(1);
    bodies.push_back(makeTestBody(sphereShape(0.1), Vec3(0.0, 0.0, 0.0), false));
    bodies.push_back(makeTestBody(sphereShape(0.1), Vec3(0.2, 0.0, 0.0), false));
    bodies.push_back(makeTestBody(sphereShape(0.1), Vec3(3.0, 0.0, 0.0), false));
    for (Body& body : bodies)
        body.generation = 1;
    std::vector<uint8_t> asleep = {0, 1, 1, 1};
    Broadphase broadphase;
    broadphase.update(bodies, kDt, 2.0, asleep.data());
    ASSERT_EQ(toVector(broadphase.pairs()), (std::vector<BodyPair>{{1, 2}}));
    const Aabb box = broadphase.bounds(1);
    bodies[1].x = Vec3(2.9, 0.0, 0.0);
    broadphase.update(bodies, kDt, 2.0, asleep.data());
    EXPECT_EQ(toVector(broadphase.pairs()), (std::vector<BodyPair>{{1, 2}}));
    EXPECT_EQ(broadphase.bounds(1).min, box.min);
    // Woken, it is searched again: paired with the ball it now touches.
    asleep[1] = 0;
    broadphase.update(bodies, kDt, 2.0, asleep.data());
    EXPECT_EQ(toVector(broadphase.pairs()), (std::vector<BodyPair>{{1, 3}}));
    EXPECT_EQ(broadphase.sleepingCount(), 2);
}

}  // namespace
}  // namespace substep
