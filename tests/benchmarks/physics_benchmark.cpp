// Benchmarks of the physics core on the shared scenes of PEERS.md: time per frame (dt = 1/60 s; the Time column is per frame)
// at the scene's own substeps, after a warm-up second. Results go to docs/PERFORMANCE.md.

#include "scenes/scene_registry.h"

#include <benchmark/benchmark.h>

namespace {

using namespace substep;

/// Steps the named built-in scene; the benchmark's argument is the substep count.
void stepScene(benchmark::State& state, const char* name) {
    SceneDescription description = findBuiltinScene(name)->build();
    description.substeps = static_cast<int>(state.range(0));
    SceneInstance instance = buildScene(description);
    for (int i = 0; i < 60; ++i) instance.world.step(description.dt);  // warm-up second
    for (auto _ : state) {
        instance.world.step(description.dt);
        benchmark::ClobberMemory();
    }
    state.counters["max_error"] = instance.world.maxJointError();
}

void BM_chain100(benchmark::State& state) { stepScene(state, "chain100"); }
void BM_rope100(benchmark::State& state) { stepScene(state, "rope100"); }
void BM_pendulum3(benchmark::State& state) { stepScene(state, "pendulum3"); }
void BM_boxes7(benchmark::State& state) { stepScene(state, "boxes7"); }

BENCHMARK(BM_chain100)->Arg(1)->Arg(5)->Arg(10)->Arg(20)->Arg(40)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_rope100)->Arg(1)->Arg(5)->Arg(10)->Arg(20)->Arg(40)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_pendulum3)->Arg(1)->Arg(5)->Arg(10)->Arg(20)->Arg(40)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_boxes7)->Arg(20)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
