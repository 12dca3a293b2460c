// What recording each constraint's corrections (engine/physics/substep_corrections.h) costs a
// frame, and that stepping a frame a substep at a time through the engine layer costs what a
// whole step does: chain100 (joints) and pyramid10 (contacts) at their own settings, after a
// warm-up second. Arg 0: plain step; 1: recording on; 2: beginFrame + each substep + finishFrame
// through ecs::PhysicsSystem (state written back after every substep), recording on.

#include "scenes/scene_registry.h"

#include <benchmark/benchmark.h>

namespace {

using namespace substep;

void stepRecorded(benchmark::State& state, const char* name) {
    const SceneDescription description = findBuiltinScene(name)->build();
    const double dt = description.dt;
    SceneInstance scene = buildScene(description);
    for (int i = 0; i < 60; ++i)
        scene.physics().step(dt);
    const int mode = static_cast<int>(state.range(0));
    scene.physics().recordCorrections(mode > 0);
    for (auto _ : state) {
        ecs::PhysicsSystem physics = scene.physics();
        if (mode < 2) {
            physics.step(dt);
        } else {
            physics.beginFrame(dt);
            while (physics.substep()) {
            }
            physics.finishFrame();
        }
        benchmark::ClobberMemory();
    }
}

void BM_corrections_chain100(benchmark::State& state) {
    stepRecorded(state, "chain100");
}
void BM_corrections_pyramid10(benchmark::State& state) {
    stepRecorded(state, "pyramid10");
}

BENCHMARK(BM_corrections_chain100)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_corrections_pyramid10)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond);

}  // namespace
