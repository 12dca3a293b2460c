// Benchmarks of the paper's gallery scenes at their Table 1 settings (dt 1/60 s, 20 substeps,
// 1 iteration), stepped with their scripts as every command steps them: time per frame after a
// warm-up second, the scene running on from there. The paper's figure is the `paper_ms` counter.
// Results go to docs/PERFORMANCE.md.

#include "scenes/live_scene.h"
#include "scenes/scene_registry.h"

#include <benchmark/benchmark.h>

namespace {

using namespace substep;

void stepGalleryScene(benchmark::State& state, const SceneEntry* entry) {
    LiveScene scene(entry->build(), entry);
    for (int i = 0; i < 60; ++i) scene.step();  // warm-up second
    for (auto _ : state) {
        scene.step();
        benchmark::ClobberMemory();
    }
    state.counters["paper_ms"] = entry->paperMsPerFrame;
}

/// One benchmark per gallery scene, registered at start-up from the scene table.
const bool kRegistered = [] {
    for (const char* name : {"joint_types", "bunny_chain", "cradle", "marbles_on_wire", "coin", "robot_arm",
                             "twisted_rope"}) {
        const SceneEntry* entry = findBuiltinScene(name);
        if (entry == nullptr) continue;
        benchmark::RegisterBenchmark((std::string("BM_gallery/") + name).c_str(), stepGalleryScene, entry)
            ->Unit(benchmark::kMillisecond);
    }
    return true;
}();

}  // namespace
