#include "run_command.h"

#include "atomic_file.h"
#include "command_options.h"
#include "csv_writer.h"
#include "knob_settings.h"
#include "output_transaction.h"
#include "scene_source.h"
#include "state_columns.h"

#include "scene/scene_loader.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <vector>

namespace substep {

namespace {

/// The options once checked: every value within its accepted range.
struct RunSettings {
    std::optional<long long> frames;
    std::optional<double> seconds;
    std::optional<int> substeps;
    std::optional<int> iterations;
    std::optional<double> dt;
    std::optional<JointProjection> jointProjection;
    std::optional<bool> sweptRestitution;
};

RunSettings checkOptions(const RunOptions& options) {
    RunSettings settings;
    if (!options.frames.empty() && !options.seconds.empty()) {
        throw UsageError("--frames and --seconds cannot be used together");
    }
    if (!options.frames.empty()) {
        settings.frames = parseInteger("--frames", options.frames, 0, kMaxFrames);
    }
    if (!options.seconds.empty())
        settings.seconds = parsePositiveReal("--seconds", options.seconds);
    if (!options.substeps.empty()) {
        settings.substeps =
            static_cast<int>(parseInteger("--substeps", options.substeps, 1, kMaxSubsteps));
    }
    if (!options.iterations.empty()) {
        settings.iterations =
            static_cast<int>(parseInteger("--iterations", options.iterations, 1, kMaxIterations));
    }
    // The bounds of a scene file's dt: 1e-320 or 1e300 went NaN at frame 1.
    if (!options.dt.empty())
        settings.dt = parseRealWithin("--dt", options.dt, kMinTimeStep, kMaxTimeStep);
    if (!options.jointProjection.empty())
        settings.jointProjection =
            parseJointProjection("--joint-projection", options.jointProjection);
    if (!options.restitution.empty())
        settings.sweptRestitution = parseSweptRestitution("--restitution", options.restitution);
    return settings;
}

/// frames = round(T / dt) (DESIGN.md), --seconds 5 when neither is given.
long long frameCount(const RunSettings& settings, double dt) {
    if (settings.frames) return *settings.frames;
    return framesForSeconds(settings.seconds.value_or(kDefaultSeconds), dt, kMaxFrames);
}

bool allFinite(const std::vector<double>& values) {
    return std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
}

/// What the run measured, for --json and the printed summary.
struct RunSummary {
    long long frames = 0;  ///< frames actually stepped (fewer when the state went non-finite)
    int substeps = 0;
    int iterations = 0;
    double wallMsPerFrame = 0.0;
    double energyInitial = 0.0;
    double energyFinal = 0.0;
    double maxError = 0.0;  ///< largest max_error over every row
    bool finite = true;
};

std::string summaryJson(const std::string& scene, const RunSummary& summary) {
    // Field order is part of what people read; nlohmann writes doubles in shortest round-trip
    // form and non-finite ones as null (JSON has no NaN).
    nlohmann::ordered_json json;
    json["scene"] = scene;
    json["frames"] = summary.frames;
    json["substeps"] = summary.substeps;
    json["iterations"] = summary.iterations;
    json["wall_ms_per_frame"] = summary.wallMsPerFrame;
    json["energy_initial"] = summary.energyInitial;
    json["energy_final"] = summary.energyFinal;
    json["max_error"] = summary.maxError;
    json["finite"] = summary.finite;
    return json.dump(2) + "\n";
}

void printSummary(const SceneSource& source, const RunSummary& summary, double dt) {
    const SceneDescription& scene = source.description;
    if (source.builtin)
        std::printf("scene      %s (built-in)\n", source.label.c_str());
    else
        std::printf("scene      %s (%s)\n", scene.name.c_str(), source.label.c_str());
    std::printf("bodies     %zu\n", scene.bodies.size());
    std::printf("joints     %zu\n", scene.joints.size());
    std::printf("frames     %lld of %.6g s = %.6g s\n", summary.frames, dt,
                static_cast<double>(summary.frames) * dt);
    std::printf("solver     %d substeps x %d iterations\n", summary.substeps, summary.iterations);
    std::printf("step time  %.4g ms/frame\n", summary.wallMsPerFrame);
    std::printf("energy     %.6g J -> %.6g J\n", summary.energyInitial, summary.energyFinal);
    std::printf("max error  %.3g m\n", summary.maxError);
    std::printf("finite     %s\n", summary.finite ? "yes" : "no");
}

int run(const RunOptions& options) {
    // Check every input before any output exists: a bad option or scene leaves no file behind.
    const RunSettings settings = checkOptions(options);
    const int threads = parseThreads(options.threads);
    const std::vector<KnobSetting> knobs = parseKnobSettings(options.knobs);
    SceneSource source = resolveScene(options.scene);
    SceneDescription& description = source.description;
    if (settings.substeps) description.substeps = *settings.substeps;
    if (settings.iterations) description.iterations = *settings.iterations;
    if (settings.dt) description.dt = *settings.dt;
    if (settings.jointProjection) description.jointProjection = *settings.jointProjection;
    if (settings.sweptRestitution) description.sweptRestitution = *settings.sweptRestitution;
    const double dt = description.dt;
    const long long frames = frameCount(settings, dt);
    LiveScene live = startLabelledScene(source, description);
    SceneInstance& scene = live.instance();
    const World& world = live.world();
    applyKnobSettings(live, knobs, source.label);
    // --substeps and --iterations win over a knob that switches the solver.
    ecs::PhysicsSystem physics = live.physics();
    WorldSettings solver = physics.settings();
    if (settings.substeps) solver.substeps = *settings.substeps;
    if (settings.iterations) solver.iterations = *settings.iterations;
    solver.threads = threads;
    if (settings.jointProjection) solver.jointProjection = *settings.jointProjection;
    if (settings.sweptRestitution) solver.sweptRestitution = *settings.sweptRestitution;
    physics.setSettings(solver);

    // The outputs are checked (not the scene file, not each other, regular files) before the
    // first frame, and appear together at the end.
    OutputTransaction outputs(source.builtin ? std::vector<std::string>{}
                                             : std::vector<std::string>{options.scene});
    AtomicFile* csvFile = !options.csvPath.empty() ? &outputs.add("--csv", options.csvPath) : nullptr;
    AtomicFile* jsonFile = !options.jsonPath.empty() ? &outputs.add("--json", options.jsonPath) : nullptr;
    std::optional<CsvWriter> csv;
    if (csvFile) {
        csv.emplace(*csvFile);
        csv->writeHeader(stateColumnNames(scene));
    }

    RunSummary summary{.substeps = world.settings().substeps,
                       .iterations = world.settings().iterations};
    std::vector<double> row;
    sampleState(scene, 0.0, row);
    if (csv) csv->writeRow(0, row);
    summary.energyInitial = summary.energyFinal = row[kStateEnergy];
    summary.maxError = row[kStateMaxError];
    summary.finite = world.isFinite() && allFinite(row);

    // The frame loop: only the world's step is timed (LiveScene::step returns it); the script,
    // the engine layer's bookkeeping, sampling and formatting are not the solver's.
    // Ctrl-C ends a long run cleanly: the loop notices, and the temporary outputs are removed.
    const InterruptGuard interruptGuard;
    std::chrono::steady_clock::duration stepTime{};
    for (long long frame = 1; frame <= frames && summary.finite; ++frame) {
        if (const int signal = interruptSignal(); signal != 0) {
            std::fprintf(stderr, "substep run: interrupted; no output written\n");
            return 128 + signal;
        }
        stepTime += live.step();
        warnAboutDroppedContacts("run", world, frame);

        // t is frame * dt, not a running sum, so it carries no accumulated rounding.
        sampleState(scene, static_cast<double>(frame) * dt, row);
        if (csv) csv->writeRow(frame, row);
        summary.frames = frame;
        summary.energyFinal = row[kStateEnergy];
        summary.maxError = std::max(summary.maxError, row[kStateMaxError]);
        summary.finite = world.isFinite() && allFinite(row);
    }
    if (summary.frames > 0) {
        summary.wallMsPerFrame = std::chrono::duration<double, std::milli>(stepTime).count() /
                                 static_cast<double>(summary.frames);
    }

    // Outputs appear only now, whole, and together: if one cannot be written, none is.
    if (jsonFile) jsonFile->write(summaryJson(source.label, summary));
    outputs.commit();

    printSummary(source, summary, dt);
    if (!summary.finite) {
        std::fprintf(stderr,
                     "substep run: the state turned non-finite at frame %lld; stopped there "
                     "(the last row written is the first non-finite one)\n",
                     summary.frames);
        return 1;
    }
    return 0;
}

}  // namespace

CLI::App* addRunCommand(CLI::App& app, RunOptions& options) {
    CLI::App* command = app.add_subcommand("run", "Headless simulation; prints a summary");
    command->add_option("SCENE", options.scene, "A built-in scene name or a .json scene file")
        ->required();
    command->add_option("--frames", options.frames, "Frames to simulate (default: --seconds 5)")
        ->type_name("N");
    command->add_option("--seconds", options.seconds, "Simulated time; frames = round(T/dt)")
        ->type_name("T")
        ->excludes("--frames");
    command->add_option("--substeps", options.substeps, "Substeps per frame (1-10000)")
        ->type_name("N");
    command->add_option("--iterations", options.iterations, "Iterations per substep (1-1000)")
        ->type_name("N");
    command->add_option("--dt", options.dt, "Frame length in seconds (default: the scene's)")
        ->type_name("S");
    command->add_option("--csv", options.csvPath, "Write a row per frame, row 0 the initial state")
        ->type_name("F");
    command->add_option("--set", options.knobs, "Turn a scene knob, e.g. --set velocity_pass=0 (repeatable)")
        ->type_name("NAME=VALUE");
    command->add_option("--json", options.jsonPath, "Write the summary as JSON")->type_name("F");
    command->add_option("--threads", options.threads, "Threads the step uses (default 1; 1-64)")
        ->type_name("N");
    command->add_option("--joint-projection", options.jointProjection,
                        "Joint directions: paper (current state) or start (substep start)")
        ->type_name("paper|start");
    command->add_option("--restitution", options.restitution,
                        "Restitution: swept (two-body collisions, any order) or paper (Eq. 34 alone)")
        ->type_name("swept|paper");
    return command;
}

int runCommand(const RunOptions& options) {
    return runReportingErrors("run", [&] { return run(options); });
}

}  // namespace substep
