// Benchmarks of contact piles (issue 18): spheres1000 after 6 s and spheres1000's layout with
// 0.2 m cubes for spheres (a pile that comes to rest), with sleeping off and on; the
// family of N spheres in a walled box (N = 1000, 4000, 16000, the box's floor growing with N so
// that the pile's depth stays the same), to see how the cost grows with N; and spheres1000 at 1
// and 2 threads. Time per frame (dt = 1/60 s, 20 substeps). Results go to docs/PERFORMANCE.md.

#include "scenes/scene_registry.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace {

using namespace substep;

/// N spheres (r 0.1 m, 1 kg, friction 0.5, restitution 0.1) in 10 layers of a square grid at
/// 0.25 m pitch, dropped into a walled box 0.3 m wider than the grid: spheres1000's layout
/// (a 10 x 10 grid in a 3 m box) scaled in its floor only.
SceneDescription spheresInABox(int count) {
    const int side = static_cast<int>(std::lround(std::sqrt(count / 10.0)));
    SceneDescription scene{.name = "spheres" + std::to_string(count), .gravity = Vec3(0, -10, 0), .substeps = 20};
    const BodyDef surface{.staticFriction = 0.5, .dynamicFriction = 0.5, .restitution = 0.1};
    BodyDef ground = surface;
    ground.shape = planeShape(Vec3::UnitY(), 0.0);
    ground.type = BodyType::Static;
    scene.bodies.push_back({"ground", ground});
    constexpr double kPitch = 0.25;
    constexpr double kWall = 0.2;
    constexpr double kHeight = 1.5;
    const double inside = side * kPitch + 0.5;
    for (int wall = 0; wall < 4; ++wall) {
        const bool alongX = wall < 2;
        const double offset = (wall % 2 == 0 ? -1.0 : 1.0) * 0.5 * (inside + kWall);
        BodyDef def = surface;
        def.shape = boxShape(alongX ? Vec3(inside + 2 * kWall, kHeight, kWall) : Vec3(kWall, kHeight, inside));
        def.type = BodyType::Static;
        def.position = alongX ? Vec3(0.0, 0.5 * kHeight, offset) : Vec3(offset, 0.5 * kHeight, 0.0);
        scene.bodies.push_back({"wall" + std::to_string(wall + 1), def});
    }
    for (int y = 0; y < 10; ++y)
        for (int z = 0; z < side; ++z)
            for (int x = 0; x < side; ++x) {
                const double shift = 0.01 * (y % 3);
                BodyDef def = surface;
                def.shape = sphereShape(0.1);
                def.mass = 1.0;
                def.position = Vec3((x - 0.5 * (side - 1)) * kPitch + shift, 0.5 + y * kPitch,
                                    (z - 0.5 * (side - 1)) * kPitch - shift);
                scene.bodies.push_back({"", def});
            }
    return scene;
}

void setThreadsAndSleeping(SceneInstance& scene, int threads, bool sleeping) {
    WorldSettings settings = scene.world().settings();
    settings.threads = threads;
    settings.sleeping = sleeping;
    scene.physics().setSettings(settings);
}

/// spheres1000 after 6 s (settled), sleeping off (0); or on (1), after the pile has fallen
/// asleep (about 20 s, at most 60 s).
void BM_spheres1000_settled(benchmark::State& state) {
    SceneInstance scene = buildScene(findBuiltinScene("spheres1000")->build());
    const bool sleeping = state.range(0) != 0;
    setThreadsAndSleeping(scene, 1, sleeping);
    const double dt = 1.0 / 60.0;
    for (int i = 0; i < 360; ++i) scene.physics().step(dt);
    for (int i = 0; sleeping && i < 3240 && scene.world().sleepingBodyCount() < 1000; ++i)
        scene.physics().step(dt);
    for (auto _ : state) {
        scene.physics().step(dt);
        benchmark::ClobberMemory();
    }
    state.counters["sleeping"] = scene.world().sleepingBodyCount();
    state.counters["contacts"] = scene.world().activeContactCount();
    state.counters["penetration_mm"] = 1e3 * scene.world().maxPenetration();
}

/// N spheres in a box, frames 61 to 120 (falling, landing, piling): args N, threads. The same
/// frames at every N (a fixed iteration count), so that the family compares like with like:
/// left to Google Benchmark, 1000 spheres ran 356 frames into the settled pile and 16000 ran
/// 11 frames of the fall.
void BM_spheres_in_a_box(benchmark::State& state) {
    SceneInstance scene = buildScene(spheresInABox(static_cast<int>(state.range(0))));
    setThreadsAndSleeping(scene, static_cast<int>(state.range(1)), false);
    const double dt = 1.0 / 60.0;
    for (int i = 0; i < 60; ++i) scene.physics().step(dt);
    long long contacts = 0;
    for (auto _ : state) {
        scene.physics().step(dt);
        contacts += scene.world().activeContactCount();
        benchmark::ClobberMemory();
    }
    state.counters["contacts"] = static_cast<double>(contacts) / static_cast<double>(state.iterations());
}

/// spheres1000 itself, frames from 1 s, at 1, 2 and 3 threads; 0: one thread in the coloured
/// order the parallel solve uses (WorldSettings::colouredSolve), the same bytes as 2 and 3.
void BM_spheres1000_threads(benchmark::State& state) {
    SceneInstance scene = buildScene(findBuiltinScene("spheres1000")->build());
    setThreadsAndSleeping(scene, std::max(static_cast<int>(state.range(0)), 1), false);
    if (state.range(0) == 0) {
        WorldSettings settings = scene.world().settings();
        settings.colouredSolve = true;
        scene.physics().setSettings(settings);
    }
    const double dt = 1.0 / 60.0;
    for (int i = 0; i < 60; ++i) scene.physics().step(dt);
    for (auto _ : state) {
        scene.physics().step(dt);
        benchmark::ClobberMemory();
    }
}

/// spheres1000's layout with a 0.2 m cube in place of every sphere: the columns land flat and
/// rest within 2 s. After 3 s, sleeping off (0) or on (1).
void BM_boxes1000_settled(benchmark::State& state) {
    SceneDescription description = findBuiltinScene("spheres1000")->build();
    for (SceneBody& body : description.bodies)
        if (body.def.shape.type == ShapeType::Sphere) body.def.shape = boxShape(Vec3::Constant(0.2));
    SceneInstance scene = buildScene(description);
    setThreadsAndSleeping(scene, 1, state.range(0) != 0);
    const double dt = 1.0 / 60.0;
    for (int i = 0; i < 180; ++i) scene.physics().step(dt);
    for (auto _ : state) {
        scene.physics().step(dt);
        benchmark::ClobberMemory();
    }
    state.counters["sleeping"] = scene.world().sleepingBodyCount();
}

BENCHMARK(BM_spheres1000_settled)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_boxes1000_settled)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_spheres_in_a_box)
    ->Args({1000, 1})
    ->Args({4000, 1})
    ->Args({16000, 1})
    ->Iterations(60)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_spheres1000_threads)->Arg(0)->Arg(1)->Arg(2)->Arg(3)->Unit(benchmark::kMillisecond);

}  // namespace
