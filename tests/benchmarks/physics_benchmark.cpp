// Benchmarks of the physics core on the shared scenes of PEERS.md: time per frame (dt = 1/60 s;
// the Time column is per frame) at the substep count given as the argument, after a warm-up
// second. The `error` counter is PEERS.md's error measure for the scene, from a separate run of
// the scene's full duration (outside the timing). Results go to docs/PERFORMANCE.md.

#include "scenes/scene_registry.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>

namespace {

using namespace substep;

SceneInstance makeScene(const char* name, int substeps, double& dt) {
    SceneDescription description = findBuiltinScene(name)->build();
    description.substeps = substeps;
    dt = description.dt;
    return buildScene(description);
}

/// chain100: relative elongation of the chain after 5 s (top anchor to last link centre).
double chainElongation(int substeps) {
    double dt = 0.0;
    SceneInstance scene = makeScene("chain100", substeps, dt);
    for (int i = 0; i < 300; ++i) scene.physics().step(dt);
    const Vec3 top(0.0, 30.0, 0.0);
    const double rest = 0.25 * 99.5;
    return ((scene.world().body(scene.namedBodyIds().back().second).x - top).norm() - rest) / rest;
}

/// rope100: largest joint gap over 5 s (m).
double ropeLargestGap(int substeps) {
    double dt = 0.0;
    SceneInstance scene = makeScene("rope100", substeps, dt);
    double largest = 0.0;
    for (int i = 0; i < 300; ++i) {
        scene.physics().step(dt);
        largest = std::max(largest, scene.world().maxJointError());
    }
    return largest;
}

/// pendulum3: |E(10 s) − E(0)| / (m g L) with m = 1 kg, g = 10, L = 1 m.
double pendulumEnergyError(int substeps) {
    double dt = 0.0;
    SceneInstance scene = makeScene("pendulum3", substeps, dt);
    const double initial = scene.world().energies().total();
    for (int i = 0; i < 600; ++i) scene.physics().step(dt);
    return std::abs(scene.world().energies().total() - initial) / 10.0;
}

void stepScene(benchmark::State& state, const char* name, double (*error)(int)) {
    const int substeps = static_cast<int>(state.range(0));
    double dt = 0.0;
    SceneInstance scene = makeScene(name, substeps, dt);
    for (int i = 0; i < 60; ++i) scene.physics().step(dt);  // warm-up second
    for (auto _ : state) {
        scene.physics().step(dt);
        benchmark::ClobberMemory();
    }
    state.counters["error"] = error(substeps);
}

void BM_chain100(benchmark::State& state) { stepScene(state, "chain100", chainElongation); }
void BM_rope100(benchmark::State& state) { stepScene(state, "rope100", ropeLargestGap); }
void BM_pendulum3(benchmark::State& state) { stepScene(state, "pendulum3", pendulumEnergyError); }

BENCHMARK(BM_chain100)->Arg(1)->Arg(5)->Arg(10)->Arg(20)->Arg(40)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_rope100)->Arg(1)->Arg(5)->Arg(10)->Arg(20)->Arg(40)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_pendulum3)->Arg(1)->Arg(5)->Arg(10)->Arg(20)->Arg(40)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
