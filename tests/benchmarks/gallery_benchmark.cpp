// Benchmarks of the paper's gallery scenes at their Table 1 settings (dt 1/60 s, their own
// substeps, 1 iteration), stepped with their scripts as every command steps them: time per frame after a
// warm-up second, the scene running on from there. The paper's figure is the `paper_ms` counter;
// the `_%` counters are each stage's share of the world's step (World::stepTimes).
// Results go to docs/PERFORMANCE.md.

#include "scenes/live_scene.h"
#include "scenes/scene_registry.h"
#include "physics/soft/soft_system.h"

#include <benchmark/benchmark.h>

namespace {

using namespace substep;

void stepGalleryScene(benchmark::State& state, const SceneEntry* entry) {
    LiveScene scene(entry->build(), entry);
    // Stage clocks on: a few clock reads per substep, under 1 % of any of these scenes.
    WorldSettings settings = scene.physics().settings();
    settings.measureTime = true;
    scene.physics().setSettings(settings);
    for (int i = 0; i < 60; ++i) scene.step();  // warm-up second
    StepTimes stages;  // summed over the timed frames: where the time goes
    for (auto _ : state) {
        scene.step();
        benchmark::ClobberMemory();
        const StepTimes& last = scene.world().stepTimes();
        stages.broadphase += last.broadphase;
        stages.narrowphase += last.narrowphase;
        stages.solve += last.solve;
        stages.velocities += last.velocities;
        stages.integrate += last.integrate;
    }
    state.counters["paper_ms"] = entry->paperMsPerFrame;
    // Each stage's share of the world's step (%).
    const double total = stages.total() > 0.0 ? stages.total() : 1.0;
    state.counters["broadphase_%"] = 100.0 * stages.broadphase / total;
    state.counters["narrowphase_%"] = 100.0 * stages.narrowphase / total;
    state.counters["solve_%"] = 100.0 * stages.solve / total;
    state.counters["velocities_%"] = 100.0 * stages.velocities / total;
    state.counters["integrate_%"] = 100.0 * stages.integrate / total;
}

/// One benchmark per gallery scene, registered at start-up from the scene table.
const bool kRegistered = [] {
    for (const char* name : {"joint_types", "bunny_chain", "cradle", "marbles_on_wire", "coin", "robot_arm",
                             "twisted_rope", "rolling_balls", "rc_car"}) {
        const SceneEntry* entry = findBuiltinScene(name);
        if (entry == nullptr) continue;
        benchmark::RegisterBenchmark((std::string("BM_gallery/") + name).c_str(), stepGalleryScene, entry)
            ->Unit(benchmark::kMillisecond);
    }
    return true;
}();

}  // namespace

namespace {

/// One element sweep over rc_car's four tyres (4416 elements) after a warm-up second of
/// driving: the cost of the shape matching with the car's batch data, which does not fit in L2.
void BM_CarElementSweep(benchmark::State& state) {
    const SceneEntry* entry = substep::findBuiltinScene("rc_car");
    substep::LiveScene scene(entry->build(), entry);
    for (int i = 0; i < 60; ++i) scene.step();
    substep::SoftSystem soft = *scene.world().softBodies();
    const double h = 1.0 / 60.0 / 20.0;
    for (auto _ : state) soft.solveElements(1.0 / (h * h));
    state.counters["ns_per_element"] = benchmark::Counter(
        static_cast<double>(soft.elementCount()), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_CarElementSweep)->Unit(benchmark::kMicrosecond);

/// One damping pass (SoftSystem::damp, once a frame) over rc_car's four tyres after a warm-up
/// second of driving: eight lanes where the CPU has AVX-512 (argument 0), four lanes (1). Each
/// pass moves the velocities further towards the elements' rigid motions, at the same cost.
void BM_CarElementDamping(benchmark::State& state) {
    const SceneEntry* entry = substep::findBuiltinScene("rc_car");
    substep::LiveScene scene(entry->build(), entry);
    for (int i = 0; i < 60; ++i) scene.step();
    substep::SoftSystem soft = *scene.world().softBodies();
    const auto lanes = state.range(0) == 0 ? substep::ElementLanes::Widest : substep::ElementLanes::Four;
    for (auto _ : state) soft.damp(1.0 / 60.0, nullptr, lanes);
    state.counters["ns_per_element"] = benchmark::Counter(
        static_cast<double>(soft.elementCount()), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_CarElementDamping)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

}  // namespace
