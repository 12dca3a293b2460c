// The cost of the engine layer: a frame stepped through the physics system (patched components
// applied, the world stepped, poses, velocities and joint readouts written back into components)
// against the world's step alone, timed inside the same call (PhysicsSystem::step returns it).
// The difference is the layer's overhead; docs/PERFORMANCE.md records it (goal: under 5 %).

#include "scene/scene.h"
#include "scenes/scene_registry.h"

#include <benchmark/benchmark.h>

#include <chrono>

namespace {

using namespace substep;

SceneInstance settledScene(const char* name) {
    const SceneEntry* entry = findBuiltinScene(name);
    const SceneDescription description = entry->build();
    SceneInstance scene = buildScene(description);
    for (int i = 0; i < 60; ++i) scene.physics().step(description.dt);  // a warm-up second
    return scene;
}

/// Whole frames through the layer: what `run` and the window pay.
void throughTheLayer(benchmark::State& state, const char* name) {
    SceneInstance scene = settledScene(name);
    const double dt = findBuiltinScene(name)->build().dt;
    for (auto _ : state) {
        scene.physics().step(dt);
        benchmark::ClobberMemory();
    }
}

/// The same frames, timing only the world's step inside them.
void worldStepAlone(benchmark::State& state, const char* name) {
    SceneInstance scene = settledScene(name);
    const double dt = findBuiltinScene(name)->build().dt;
    for (auto _ : state) {
        const auto worldStep = scene.physics().step(dt);
        state.SetIterationTime(std::chrono::duration<double>(worldStep).count());
    }
}

const bool kRegistered = [] {
    for (const char* name : {"chain100", "spheres1000"}) {
        benchmark::RegisterBenchmark((std::string("BM_engine_layer/system/") + name).c_str(), throughTheLayer, name)
            ->Unit(benchmark::kMillisecond);
        benchmark::RegisterBenchmark((std::string("BM_engine_layer/world/") + name).c_str(), worldStepAlone, name)
            ->UseManualTime()
            ->Unit(benchmark::kMillisecond);
    }
    return true;
}();

}  // namespace
