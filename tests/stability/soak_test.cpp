// Soak (CTest label `soak`, not in the default run; issue 19): every built-in scene and every
// scene file in assets/scenes (soft_bodies.json) for 10 simulated minutes through the engine
// layer, as `substep run` steps it (LiveScene, its script included). Checked at every frame: the state stays finite. Energy: a scene nothing drives
// (no script, no joint target or motor) never gains more than 5 % of its energy scale over
// E(0); a driven one reaches a steady state, gaining no more than one energy scale over the
// largest energy of its first minute. Memory: the resident size at the end is within 10 % of
// the size after minute 1 (no growth per frame). SUBSTEP_SOAK_SECONDS shortens the run for a
// quick look (the minute-1 reference then comes at a tenth of it).

#include "error_measures.h"
#include "scene/scene_loader.h"
#include "scenes/live_scene.h"
#include "scenes/scene_registry.h"

#include <gtest/gtest.h>

#include <unistd.h>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <string>
#include <vector>

namespace substep {
namespace {

/// Resident set size of this process (bytes), from /proc/self/statm.
double residentBytes() {
    std::ifstream statm("/proc/self/statm");
    long long pages = 0;
    long long resident = 0;
    statm >> pages >> resident;
    return static_cast<double>(resident) * static_cast<double>(::sysconf(_SC_PAGESIZE));
}

double soakSeconds() {
    if (const char* text = std::getenv("SUBSTEP_SOAK_SECONDS")) return std::max(1.0, std::atof(text));
    return 600.0;
}

/// A scene injects energy when a script runs it or a joint is driven towards a target.
bool isDriven(const SceneEntry* entry, const SceneDescription& description) {
    if (entry != nullptr && entry->makeScript != nullptr) return true;
    return std::any_of(description.joints.begin(), description.joints.end(), [](const SceneJoint& joint) {
        return joint.def.targetAngle || joint.def.targetOffset || joint.def.targetVelocity;
    });
}

/// A built-in scene (`entry`) or a scene file (`file`).
struct SoakScene {
    std::string name;
    const SceneEntry* entry = nullptr;
    std::string file;
};

/// What the test lists show for a case.
void PrintTo(const SoakScene& scene, std::ostream* out) { *out << scene.name; }

class Soak : public ::testing::TestWithParam<SoakScene> {};

TEST_P(Soak, TenMinutesStayFiniteBoundedAndFlat) {
    const SoakScene& scene = GetParam();
    const SceneEntry* entry = scene.entry;
    LiveScene live(entry != nullptr ? entry->build() : loadSceneFile(scene.file), entry);
    const bool driven = isDriven(entry, live.description());
    const double scale = errorReference(entry, live.instance()).energyScale;
    const double dt = live.description().dt;
    const double seconds = soakSeconds();
    const long long frames = std::llround(seconds / dt);
    const long long referenceFrame = std::llround(std::min(60.0, seconds / 10.0) / dt);

    const double initial = live.world().energies().total();
    double firstMinuteMax = initial;
    double worstGain = 0.0;  // over E(0) (undriven) or over the first minute's largest (driven)
    double residentAtReference = 0.0;
    for (long long frame = 1; frame <= frames; ++frame) {
        live.step();
        ASSERT_TRUE(live.world().isFinite()) << scene.name << ": non-finite at frame " << frame;
        const double energy = live.world().energies().total();
        ASSERT_TRUE(std::isfinite(energy)) << scene.name << ": energy non-finite at frame " << frame;
        if (frame <= referenceFrame) {
            firstMinuteMax = std::max(firstMinuteMax, energy);
            if (!driven) worstGain = std::max(worstGain, energy - initial);
        } else {
            worstGain = std::max(worstGain, energy - (driven ? firstMinuteMax : initial));
        }
        if (frame == referenceFrame) residentAtReference = residentBytes();
    }
    const double residentAtEnd = residentBytes();
    std::printf("[ measured ] %s: %s, %.0f s, energy scale %.4g J, worst gain %.4g J (%.3g scales), "
                "resident %.1f MB after the first minute, %.1f MB at the end\n",
                scene.name.c_str(), driven ? "driven" : "undriven", seconds, scale,
                worstGain, worstGain / scale, residentAtReference / 1e6, residentAtEnd / 1e6);
    RecordProperty("worst_gain_scales", std::to_string(worstGain / scale));
    RecordProperty("resident_growth", std::to_string(residentAtEnd / residentAtReference));
    EXPECT_LE(worstGain, (driven ? 1.0 : 0.05) * scale) << scene.name;
    EXPECT_LE(residentAtEnd, 1.10 * residentAtReference) << scene.name;
}

std::vector<SoakScene> everyScene() {
    std::vector<SoakScene> scenes;
    for (const SceneEntry& entry : builtinScenes()) scenes.push_back({std::string(entry.name), &entry, {}});
    std::vector<std::filesystem::path> files;
    for (const auto& item : std::filesystem::directory_iterator(SUBSTEP_ASSET_SCENES_DIR)) {
        if (item.path().extension() == ".json") files.push_back(item.path());
    }
    std::sort(files.begin(), files.end());
    for (const auto& file : files) scenes.push_back({"file_" + file.stem().string(), nullptr, file.string()});
    return scenes;
}

INSTANTIATE_TEST_SUITE_P(Scenes, Soak, ::testing::ValuesIn(everyScene()),
                         [](const ::testing::TestParamInfo<SoakScene>& paramInfo) { return paramInfo.param.name; });

}  // namespace
}  // namespace substep
