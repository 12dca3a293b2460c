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

/// Whole frames through the layer, what `run` and the window pay; the counters split each frame
/// into the world's step and the layer's own work around it (sync, write-back), measured in the
/// same frames so that the machine's noise hits both alike.
void throughTheLayer(benchmark::State& state, const char* name) {
    SceneInstance scene = settledScene(name);
    const double dt = findBuiltinScene(name)->build().dt;
    std::chrono::steady_clock::duration world{};
    std::chrono::steady_clock::duration total{};
    for (auto _ : state) {
        const auto start = std::chrono::steady_clock::now();
        world += scene.physics().step(dt);
        total += std::chrono::steady_clock::now() - start;
        benchmark::ClobberMemory();
    }
    const double worldMs = std::chrono::duration<double, std::milli>(world).count();
    const double totalMs = std::chrono::duration<double, std::milli>(total).count();
    state.counters["world_ms"] = benchmark::Counter(worldMs, benchmark::Counter::kAvgIterations);
    state.counters["layer_%"] = worldMs > 0.0 ? 100.0 * (totalMs - worldMs) / worldMs : 0.0;
}

const bool kRegistered = [] {
    for (const char* name : {"chain100", "spheres1000"}) {
        benchmark::RegisterBenchmark((std::string("BM_engine_layer/") + name).c_str(), throughTheLayer, name)
            ->Unit(benchmark::kMillisecond);
    }
    return true;
}();

}  // namespace
