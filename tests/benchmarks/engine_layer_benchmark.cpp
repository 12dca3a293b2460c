// The cost of the engine layer: a frame stepped through the physics system (patched components
// applied, the world stepped, poses, velocities and joint readouts written back into components)
// against the world's step alone, timed inside the same call (PhysicsSystem::step returns it).
// The difference is the layer's overhead; docs/PERFORMANCE.md records it (goal: under 5 %).
// tyre1100 is a soft body alone, whose readout (centre, velocity, extent; the volume only on
// demand, ecs::softBodyReadout) the layer writes back after every step.

#include "scene/scene.h"
#include "scenes/scene_registry.h"

#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <string>
#include <string_view>

namespace {

using namespace substep;

/// An 1100-element tyre (44 x 5 x 5 cells, as soft_benchmark.cpp's) resting on the ground: what
/// the layer adds to a soft body is its readout, written back after every step.
SceneDescription tyreScene() {
    SceneDescription description;
    description.bodies.push_back({"ground", {.shape = planeShape(Vec3::UnitY(), 0.0), .type = BodyType::Static}});
    const Quat axisAlongZ(Eigen::AngleAxisd(M_PI / 2.0, Vec3::UnitX()));
    description.softBodies.push_back(
        {.name = "tyre",
         .def = {.type = SoftBodyType::Tyre, .outerRadius = 0.3, .innerRadius = 0.2, .width = 0.15,
                 .cells = {44, 5, 5}, .position = Vec3(0, 0.31, 0), .orientation = axisAlongZ,
                 .compliance = 1e-6, .damping = 5.0, .particleRadius = 0.005}});
    return description;
}

SceneDescription describe(const char* name) {
    return std::string_view(name) == "tyre1100" ? tyreScene() : findBuiltinScene(name)->build();
}

SceneInstance settledScene(const char* name) {
    const SceneDescription description = describe(name);
    SceneInstance scene = buildScene(description);
    for (int i = 0; i < 60; ++i) scene.physics().step(description.dt);  // a warm-up second
    return scene;
}

/// Whole frames through the layer, what `run` and the window pay; the counters split each frame
/// into the world's step and the layer's own work around it (sync, write-back), measured in the
/// same frames so that the machine's noise hits both alike.
void throughTheLayer(benchmark::State& state, const char* name) {
    SceneInstance scene = settledScene(name);
    const double dt = describe(name).dt;
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
    for (const char* name : {"chain100", "spheres1000", "tyre1100"}) {
        benchmark::RegisterBenchmark((std::string("BM_engine_layer/") + name).c_str(), throughTheLayer, name)
            ->Unit(benchmark::kMillisecond);
    }
    return true;
}();

}  // namespace
