// libFuzzer target for engine/scene: the scene loader (parseSceneText) and the world it builds
// (buildScene, then two frames of at most 4 substeps). Bad input must end in a SceneError; what
// loads must build and stay finite. Anything else (a crash, a sanitizer report, another
// exception, a non-finite state) is a finding, to be turned into a test in tests/scene/.
// Built with clang and -DSUBSTEP_FUZZ=ON (tests/fuzz/CMakeLists.txt).

#include "scene/scene.h"
#include "scene/scene_loader.h"

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

namespace {

/// Bounds the work of one input, so the fuzzer explores instead of simulating: a valid file may
/// ask for 10000 substeps of 100000 soft elements.
constexpr int kMaxFuzzSubsteps = 4;
constexpr std::size_t kMaxFuzzBodies = 200;

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace substep;
    SceneDescription description;
    try {
        description = parseSceneText(
            std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.json");
    } catch (const SceneError&) {
        return 0;  // rejected with a message: the expected outcome for most inputs
    }
    if (description.bodies.size() > kMaxFuzzBodies) return 0;
    if (description.substeps > kMaxFuzzSubsteps) description.substeps = kMaxFuzzSubsteps;
    description.iterations = 1;
    SceneInstance scene = buildScene(description);
    ecs::PhysicsSystem physics = scene.physics();
    for (int frame = 0; frame < 2; ++frame) physics.step(description.dt);
    if (!scene.world().isFinite()) {
        std::fprintf(stderr, "scene_loader_fuzz: a valid scene turned non-finite\n");
        std::abort();
    }
    return 0;
}
