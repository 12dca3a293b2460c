// Tests engine/physics/worker_pool.cpp and its use by the world's narrowphase (world.cpp,
// WorldSettings::threads): every chunk runs exactly once, for any chunk count, loop after loop;
// and a pile of bodies steps to the same bytes at 1 thread (in the coloured order the parallel
// solve uses, WorldSettings::colouredSolve), 2 and 3 threads, with sleeping too.

#include "physics_test_support.h"

#include "physics/worker_pool.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cstring>
#include <thread>
#include <vector>

namespace substep {
namespace {

TEST(WorkerPoolTest, EveryChunkRunsOnceInEveryLoop) {
    for (const int threads : {1, 2, 4}) {
        WorkerPool pool(threads);
        EXPECT_EQ(pool.threads(), threads);
        for (const int chunks : {0, 1, 2, 7, 64, 1000, WorkerPool::kMaxBlocks + 5}) {
            for (int loop = 0; loop < 3; ++loop) {
                std::vector<std::atomic<int>> runs(static_cast<size_t>(chunks));
                pool.parallelFor(chunks, [&](int chunk) { runs[static_cast<size_t>(chunk)].fetch_add(1); });
                int wrong = 0;
                for (const std::atomic<int>& count : runs) wrong += count.load() != 1;
                EXPECT_EQ(wrong, 0) << threads << " threads, " << chunks << " chunks, loop " << loop;
            }
        }
    }
}

TEST(WorkerPoolTest, ManyShortLoopsInARow) {
    // The hand-over between loops (a worker still finishing one as the next begins) must never
    // run a chunk twice or lose one.
    WorkerPool pool(3);
    std::vector<int> sums(5000, 0);
    for (size_t loop = 0; loop < sums.size(); ++loop) {
        std::vector<int> slots(3 + loop % 5, 0);
        pool.parallelFor(static_cast<int>(slots.size()), [&](int chunk) { slots[static_cast<size_t>(chunk)] += chunk + 1; });
        for (const int value : slots) sums[loop] += value;
        const int n = static_cast<int>(slots.size());
        ASSERT_EQ(sums[loop], n * (n + 1) / 2) << loop;
    }
}

// forEachThread runs its body once on every thread, each with its own index, and barrier()
// holds every thread until all have reached it: each round, every thread writes its slot, and
// after the barrier every thread must see every slot of that round. More threads than this
// machine's two cores too (the barrier then yields its core to the thread it waits for).
TEST(WorkerPoolTest, EveryThreadRunsOnceAndBarriersHoldThemTogether) {
    for (const int threads : {1, 2, 3, 8}) {
        WorkerPool pool(threads);
        // Fewer loops where the threads outnumber the cores: there a barrier waits for a thread
        // that must first get a core.
        const int loops = threads > 2 ? 40 : 200;
        for (int loop = 0; loop < loops; ++loop) {
            std::vector<std::atomic<int>> calls(static_cast<size_t>(threads));
            std::vector<std::atomic<int>> round(static_cast<size_t>(threads));
            std::atomic<int> behind{0};
            pool.forEachThread([&](int thread) {
                calls[static_cast<size_t>(thread)].fetch_add(1);
                uint32_t passed = 0;
                for (int r = 1; r <= 5; ++r) {
                    round[static_cast<size_t>(thread)].store(r);
                    pool.barrier(passed);
                    for (const std::atomic<int>& other : round) behind += other.load() < r;
                    pool.barrier(passed);  // no one starts the next round before all have looked
                }
            });
            for (const std::atomic<int>& count : calls) ASSERT_EQ(count.load(), 1) << threads << " threads, loop " << loop;
            ASSERT_EQ(behind.load(), 0) << threads << " threads, loop " << loop;
        }
    }
}

// More threads than the machine has CPUs never fit (forEachThread's barriers would wait for
// threads to get a core; the world's colours then keep the stealing blocks); one thread always does.
TEST(WorkerPoolTest, ThreadsFitCoresOnlyWhenEachCanHaveOne) {
    EXPECT_TRUE(WorkerPool(1).threadsFitCores());
    const int cpus = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    EXPECT_FALSE(WorkerPool(cpus + 1).threadsFitCores());
}

/// 240 spheres and boxes dropped into a walled pit, some started inside one another.
World pile(int threads, bool sleeping) {
    World world({.gravity = Vec3(0, -10, 0), .substeps = 10, .sleeping = sleeping, .threads = threads,
                 .colouredSolve = true});
    world.createBody({.shape = planeShape(Vec3::UnitY(), 0.0), .type = BodyType::Static});
    for (int side = 0; side < 4; ++side) {
        const double x = side == 0 ? -1.1 : side == 1 ? 1.1 : 0.0;
        const double z = side == 2 ? -1.1 : side == 3 ? 1.1 : 0.0;
        const Vec3 size = side < 2 ? Vec3(0.2, 2.0, 2.4) : Vec3(2.4, 2.0, 0.2);
        world.createBody({.shape = boxShape(size), .type = BodyType::Static, .position = Vec3(x, 1.0, z)});
    }
    for (int i = 0; i < 240; ++i) {
        const Vec3 position(-0.9 + 0.2 * (i % 10) + 0.01 * (i % 3), 0.15 + 0.18 * (i / 40),
                            -0.9 + 0.2 * ((i / 10) % 4) + 0.1 * ((i / 5) % 2));
        const Shape shape = i % 4 == 3 ? boxShape(Vec3(0.15, 0.12, 0.17)) : sphereShape(0.09);
        world.createBody({.shape = shape, .mass = 0.2 + 0.05 * (i % 7), .position = position,
                          .restitution = 0.1 * (i % 3)});
    }
    return world;
}

void expectSameBytes(const World& a, const World& b, const char* what) {
    ASSERT_EQ(a.bodies().size(), b.bodies().size());
    EXPECT_EQ(test::differingBodies(a, b), 0) << what;
    EXPECT_EQ(a.contacts().size(), b.contacts().size()) << what;
}

TEST(ParallelStepTest, SameBytesForEveryThreadCount) {
    for (const bool sleeping : {false, true}) {
        World serial = pile(1, sleeping);
        World two = pile(2, sleeping);
        World three = pile(3, sleeping);
        // Long enough for the pile to settle (and, with sleeping, for islands to fall asleep).
        for (int frame = 0; frame < 100; ++frame) {
            serial.step(test::kDt);
            two.step(test::kDt);
            three.step(test::kDt);
        }
        ASSERT_TRUE(serial.isFinite());
        EXPECT_GT(serial.contacts().size() + static_cast<size_t>(serial.sleepingBodyCount()), 200u);
        expectSameBytes(serial, two, sleeping ? "2 threads, sleeping" : "2 threads");
        expectSameBytes(serial, three, sleeping ? "3 threads, sleeping" : "3 threads");
    }
}

TEST(ParallelStepTest, ThreadCountMayChangeBetweenSteps) {
    World serial = pile(1, false);
    World changing = pile(1, false);
    for (int frame = 0; frame < 30; ++frame) {
        WorldSettings settings = changing.settings();
        settings.threads = 1 + frame % 4;
        changing.setSettings(settings);
        serial.step(test::kDt);
        changing.step(test::kDt);
    }
    expectSameBytes(serial, changing, "threads changing every frame");
}

}  // namespace
}  // namespace substep
