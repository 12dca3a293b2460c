#include "bench_command.h"

#include "atomic_file.h"
#include "command_options.h"
#include "output_transaction.h"
#include "scene_source.h"
#include "scenes/scene_registry.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace substep {

namespace {

/// Frames per repeat (warm-up and timed together), a sanity bound like `run`'s --frames.
constexpr long long kMaxBenchFrames = 10'000'000;

struct BenchSettings {
    double seconds = kBenchDefaultSeconds;
    int repeats = static_cast<int>(kBenchDefaultRepeats);
    int threads = 1;
    double warmUp = kBenchWarmUpSeconds;
    bool sleeping = false;
    std::optional<bool> sweptRestitution;  ///< --restitution; none: each scene's
};

BenchSettings checkOptions(const BenchOptions& options) {
    BenchSettings settings;
    if (!options.seconds.empty())
        settings.seconds = parsePositiveReal("--seconds", options.seconds, kBenchMaxSeconds);
    settings.threads = parseThreads(options.threads);
    if (!options.warmUp.empty())
        settings.warmUp = parseRealWithin("--warm-up", options.warmUp, 0.0, kBenchMaxSeconds);
    settings.sleeping = options.sleeping;
    if (!options.restitution.empty())
        settings.sweptRestitution = parseSweptRestitution("--restitution", options.restitution);
    if (!options.repeats.empty()) {
        settings.repeats =
            static_cast<int>(parseInteger("--repeats", options.repeats, 1, kBenchMaxRepeats));
    }
    return settings;
}

/// One scene to measure: its description and what the table says about it.
struct BenchScene {
    SceneSource source;
    double paperMsPerFrame = 0.0;  ///< 0: the paper gives none
    long long warmUpFrames = 0;
    long long timedFrames = 0;
};

/// What one scene measured.
struct BenchResult {
    std::vector<double> repeatMsPerFrame;  ///< each repeat's mean over its timed frames
    double medianMsPerFrame = 0.0;
    double contactsPerFrame = 0.0;  ///< mean contact points pushing at the end of a timed frame
    double sleepingPerFrame = 0.0;  ///< mean sleeping bodies at the end of a timed frame
    bool finite = true;
};

/// Bodies the solver moves; static ones (a ceiling, the ground) cost nothing per substep, and
/// the paper's Table 1 counts the moving ones ("3 Boxes").
std::size_t movingBodies(const SceneDescription& description) {
    return static_cast<std::size_t>(
        std::count_if(description.bodies.begin(), description.bodies.end(),
                      [](const SceneBody& body) { return body.def.type != BodyType::Static; }));
}

/// Resolves every SCENE (default: all built-ins) and sizes its runs. Throws on the first bad
/// one, before anything has run or been written.
std::vector<BenchScene> resolveScenes(const BenchOptions& options, const BenchSettings& settings) {
    std::vector<std::string> names = options.scenes;
    if (names.empty()) {
        for (const SceneEntry& entry : builtinScenes())
            names.emplace_back(entry.name);
    }
    std::vector<BenchScene> scenes;
    for (const std::string& name : names) {
        BenchScene scene{.source = resolveScene(name)};
        if (settings.sweptRestitution) scene.source.description.sweptRestitution = *settings.sweptRestitution;
        if (scene.source.builtin) scene.paperMsPerFrame = findBuiltinScene(name)->paperMsPerFrame;
        const double dt = scene.source.description.dt;
        // At least one frame each, so a --seconds shorter than dt still measures something.
        const double warmUp = std::max(1.0, std::round(settings.warmUp / dt));
        const double timed = std::max(1.0, std::round(settings.seconds / dt));
        if (!(warmUp + timed <= static_cast<double>(kMaxBenchFrames))) {
            throw UsageError(name + ": --seconds " + std::to_string(settings.seconds) + " at dt " +
                             std::to_string(dt) + " is more than " +
                             std::to_string(kMaxBenchFrames) + " frames");
        }
        scene.warmUpFrames = static_cast<long long>(warmUp);
        scene.timedFrames = static_cast<long long>(timed);
        // A scene that cannot be built fails here, before any output.
        buildLabelledScene(scene.source.description, scene.source.label);
        scenes.push_back(std::move(scene));
    }
    return scenes;
}

/// Thrown out of the frame loop on Ctrl-C; carries the exit code.
struct Interrupted {
    int exitCode;
};

double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    const std::size_t middle = values.size() / 2;
    if (values.size() % 2 == 1) return values[middle];
    return 0.5 * (values[middle - 1] + values[middle]);
}

/// Runs one scene: every repeat from a fresh build, warm-up untimed, then only world.step
/// timed. A scene that turns non-finite stops at once; its figures are then meaningless.
BenchResult measure(const BenchScene& scene, const BenchSettings& settings) {
    BenchResult result;
    for (int repeat = 0; repeat < settings.repeats && result.finite; ++repeat) {
        LiveScene live = startLabelledScene(scene.source);
        const World& world = live.world();
        if (settings.threads != 1 || settings.sleeping) {
            ecs::PhysicsSystem physics = live.physics();
            WorldSettings changed = physics.settings();
            changed.threads = settings.threads;
            changed.sleeping = changed.sleeping || settings.sleeping;
            physics.setSettings(changed);
        }
        std::chrono::steady_clock::duration stepTime{};
        long long contactSum = 0;
        long long sleepingSum = 0;
        const long long frames = scene.warmUpFrames + scene.timedFrames;
        for (long long frame = 0; frame < frames; ++frame) {
            if (const int signal = interruptSignal(); signal != 0) throw Interrupted{128 + signal};
            const auto worldStep = live.step();
            if (frame >= scene.warmUpFrames) {
                stepTime += worldStep;
                contactSum += world.activeContactCount();
                sleepingSum += world.sleepingBodyCount();
            }
            if (!world.isFinite()) {
                result.finite = false;
                break;
            }
        }
        if (!result.finite) break;
        result.contactsPerFrame = static_cast<double>(contactSum) / static_cast<double>(scene.timedFrames);
        result.sleepingPerFrame = static_cast<double>(sleepingSum) / static_cast<double>(scene.timedFrames);
        result.repeatMsPerFrame.push_back(
            std::chrono::duration<double, std::milli>(stepTime).count() /
            static_cast<double>(scene.timedFrames));
    }
    if (result.finite) result.medianMsPerFrame = median(result.repeatMsPerFrame);
    return result;
}

/// The table, Table 1's columns. Rows print as their scene finishes, so they are the progress.
class BenchTable {
  public:
    explicit BenchTable(const std::vector<BenchScene>& scenes) {
        for (const BenchScene& scene : scenes)
            nameWidth_ = std::max(nameWidth_, static_cast<int>(scene.source.label.size()));
    }

    void printHeader() const {
        std::printf("%-*s  %6s  %6s  %14s  %8s  %10s  %10s  %14s  %10s\n", nameWidth_, "scene",
                    "bodies", "joints", "contacts/frame", "substeps", "iterations", "ms/frame",
                    "paper ms/frame", "paper/ours");
        std::fflush(stdout);
    }

    void printRow(const BenchScene& scene, const BenchResult& result) const {
        const SceneDescription& description = scene.source.description;
        std::string ours = "non-finite";
        std::string paper;
        std::string ratio;
        if (result.finite) ours = format("%.4g", result.medianMsPerFrame);
        if (scene.paperMsPerFrame > 0.0) {
            paper = format("%.3g", scene.paperMsPerFrame);
            if (result.finite && result.medianMsPerFrame > 0.0)
                ratio = format("%.1fx", scene.paperMsPerFrame / result.medianMsPerFrame);
        }
        const std::string row =
            format("%-*s  %6zu  %6zu  %14.0f  %8d  %10d  %10s  %14s  %10s", nameWidth_,
                   scene.source.label.c_str(), movingBodies(description), description.joints.size(),
                   result.contactsPerFrame, description.substeps, description.iterations, ours.c_str(), paper.c_str(),
                   ratio.c_str());
        // Blank trailing columns leave no trailing spaces.
        std::printf("%s\n", row.substr(0, row.find_last_not_of(' ') + 1).c_str());
        std::fflush(stdout);
    }

  private:
    template <typename... Args>
    static std::string format(const char* pattern, Args... args) {
        const int size = std::snprintf(nullptr, 0, pattern, args...);
        std::string text(static_cast<std::size_t>(size) + 1, '\0');
        std::snprintf(text.data(), text.size(), pattern, args...);
        text.resize(static_cast<std::size_t>(size));
        return text;
    }

    int nameWidth_ = 5;  // "scene"
};

/// One object per scene, the table's columns plus what the run was (frames, repeats).
nlohmann::ordered_json resultJson(const BenchScene& scene, const BenchResult& result,
                                  const BenchSettings& settings) {
    const SceneDescription& description = scene.source.description;
    nlohmann::ordered_json json;
    json["scene"] = scene.source.label;
    json["bodies"] = movingBodies(description);
    json["static_bodies"] = description.bodies.size() - movingBodies(description);
    json["joints"] = description.joints.size();
    json["contacts_per_frame"] = result.contactsPerFrame;
    json["substeps"] = description.substeps;
    json["iterations"] = description.iterations;
    json["dt"] = description.dt;
    json["warm_up_frames"] = scene.warmUpFrames;
    json["timed_frames"] = scene.timedFrames;
    json["repeats"] = settings.repeats;
    json["repeat_ms_per_frame"] = result.repeatMsPerFrame;
    json["median_ms_per_frame"] = nullptr;
    if (result.finite) json["median_ms_per_frame"] = result.medianMsPerFrame;
    json["paper_ms_per_frame"] = nullptr;
    json["paper_ratio"] = nullptr;
    if (scene.paperMsPerFrame > 0.0) {
        json["paper_ms_per_frame"] = scene.paperMsPerFrame;
        if (result.finite && result.medianMsPerFrame > 0.0)
            json["paper_ratio"] = scene.paperMsPerFrame / result.medianMsPerFrame;
    }
    json["finite"] = result.finite;
    if (settings.sleeping) json["sleeping_bodies_per_frame"] = result.sleepingPerFrame;
    return json;
}

int bench(const BenchOptions& options) {
    // Check every input before anything runs or exists: bad options, scenes or an unwritable
    // --json path leave no file behind and cost no benchmark time.
    const BenchSettings settings = checkOptions(options);
    const std::vector<BenchScene> scenes = resolveScenes(options, settings);
    std::vector<std::string> inputs;
    for (const BenchScene& scene : scenes)
        if (!scene.source.builtin) inputs.push_back(scene.source.label);
    OutputTransaction outputs(inputs);
    AtomicFile* jsonFile = options.jsonPath.empty() ? nullptr : &outputs.add("--json", options.jsonPath);

    const BenchTable table(scenes);
    table.printHeader();
    // Ctrl-C ends a long bench cleanly: the loop notices, and the temporary output is removed.
    const InterruptGuard interruptGuard;
    nlohmann::ordered_json json = nlohmann::ordered_json::array();
    std::vector<std::string> nonFinite;
    for (const BenchScene& scene : scenes) {
        BenchResult result;
        try {
            result = measure(scene, settings);
        } catch (const Interrupted& interrupted) {
            std::fprintf(stderr, "substep bench: interrupted; no output written\n");
            return interrupted.exitCode;
        }
        table.printRow(scene, result);
        if (settings.sleeping && result.finite)
            std::printf("  %s: %.4g of %zu moving bodies asleep (mean over the timed frames)\n",
                        scene.source.label.c_str(), result.sleepingPerFrame,
                        movingBodies(scene.source.description));
        json.push_back(resultJson(scene, result, settings));
        if (!result.finite) nonFinite.push_back(scene.source.label);
    }
    std::printf(
        "ms/frame: median of %d repeat%s of %.6g s each after a %.6g s warm-up, world step "
        "only, %d thread%s%s\n"
        "bodies: moving ones; paper: Table 1 (3.6 GHz Core i7); paper/ours > 1: faster "
        "here\n",
        settings.repeats, settings.repeats == 1 ? "" : "s", settings.seconds, settings.warmUp,
        settings.threads, settings.threads == 1 ? "" : "s", settings.sleeping ? ", sleeping on" : "");

    if (jsonFile) {
        jsonFile->write(json.dump(2) + "\n");
        outputs.commit();
    }
    if (!nonFinite.empty()) {
        std::string names;
        for (const std::string& name : nonFinite)
            names += (names.empty() ? "" : ", ") + name;
        std::fprintf(stderr, "substep bench: the state turned non-finite in %s\n", names.c_str());
        return 1;
    }
    return 0;
}

}  // namespace

CLI::App* addBenchCommand(CLI::App& app, BenchOptions& options) {
    CLI::App* command =
        app.add_subcommand("bench", "Milliseconds per frame per scene, like the paper's Table 1");
    command->add_option("SCENE", options.scenes,
                        "Built-in scene names or .json scene files (default: every built-in)");
    command->add_option("--json", options.jsonPath, "Write the table as a JSON array")
        ->type_name("F");
    command
        ->add_option("--seconds", options.seconds,
                     "Simulated time timed per repeat, after a 1 s warm-up (default 3)")
        ->type_name("T");
    command
        ->add_option("--repeats", options.repeats,
                     "Repeats per scene, each from a fresh build "
                     "(1-100, default 3); the median is reported")
        ->type_name("N");
    command->add_option("--threads", options.threads, "Threads the step uses (default 1; 1-64)")
        ->type_name("N");
    command
        ->add_option("--warm-up", options.warmUp,
                     "Simulated time run untimed before the timed seconds (default 1; 0-3600)")
        ->type_name("T");
    command->add_flag("--sleeping", options.sleeping,
                      "Turn sleeping on in every scene (WorldSettings::sleeping; measure a settled "
                      "pile with a --warm-up long enough for it to fall asleep)");
    command->add_option("--restitution", options.restitution,
                        "Restitution: swept (two-body collisions, any order) or paper (Eq. 34 alone)")
        ->type_name("swept|paper");
    return command;
}

int benchCommand(const BenchOptions& options) {
    return runReportingErrors("bench", [&] { return bench(options); });
}

}  // namespace substep
