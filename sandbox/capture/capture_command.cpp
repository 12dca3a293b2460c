#include "capture/capture_command.h"

#include "capture/capture_report.h"
#include "capture/capture_runner.h"
#include "capture/capture_script.h"
#include "capture/golden_files.h"
#include "capture/json_input.h"
#include "capture/state_file.h"
#include "command_options.h"
#include "render/png_codec.h"

#include <unistd.h>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>

namespace substep {

namespace {

using namespace capture;
namespace fs = std::filesystem;

/// A capture's goldens, read and checked before anything runs.
struct Goldens {
    std::map<long long, CaptureState> states;
    std::map<long long, render::Image> images;
    std::string digest;  ///< empty without `state`
};

/// "capture K/N NAME: frame F/LAST" on one rewritten line of a terminal; silent otherwise.
class ProgressLine {
  public:
    ProgressLine() : enabled_(isatty(STDERR_FILENO) == 1) {}
    ~ProgressLine() { clear(); }

    void show(std::size_t ordinal, std::size_t total, const std::string& name, long long frame,
              long long last) {
        if (!enabled_ || (frame % 10 != 0 && frame != last)) return;
        std::fprintf(stderr, "\r\033[Kcapture %zu/%zu %s: frame %lld/%lld", ordinal, total,
                     name.c_str(), frame, last);
        std::fflush(stderr);
        shown_ = true;
    }
    void clear() {
        if (!shown_) return;
        std::fprintf(stderr, "\r\033[K");
        std::fflush(stderr);
        shown_ = false;
    }

  private:
    bool enabled_;
    bool shown_ = false;
};

std::string percent(double fraction) {
    char text[32];
    std::snprintf(text, sizeof text, "%.4g%%", 100.0 * fraction);
    return text;
}

std::string shortNumber(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", value);
    return text;
}

/// The captures --only selects (all without it). Throws UsageError for a name the script lacks.
std::vector<const CaptureSpec*> selectCaptures(const CaptureScript& script,
                                               const std::vector<std::string>& only) {
    std::vector<const CaptureSpec*> selected;
    for (const std::string& name : only) {
        const bool known = std::any_of(script.captures.begin(), script.captures.end(),
                                       [&](const CaptureSpec& spec) { return spec.name == name; });
        if (!known) {
            std::string names;
            for (const CaptureSpec& spec : script.captures)
                names += (names.empty() ? "" : ", ") + spec.name;
            throw UsageError("--only " + name + ": " + script.file +
                             " has no capture of that name (its captures: " + names + ")");
        }
    }
    for (const CaptureSpec& spec : script.captures) {
        if (only.empty() || std::find(only.begin(), only.end(), spec.name) != only.end())
            selected.push_back(&spec);
    }
    return selected;
}

Goldens readGoldens(const CaptureScript& script, const CaptureSpec& spec) {
    const std::string folder = captureFolder(script.goldenFolder, spec.name);
    Goldens goldens;
    for (const long long frame : spec.frames) {
        if (spec.state) {
            goldens.states[frame] =
                readGoldenState((fs::path(folder) / stateFileName(frame)).string(), script.file);
        }
        if (spec.image) {
            goldens.images[frame] =
                readGoldenImage((fs::path(folder) / imageFileName(frame)).string(), script.file);
        }
    }
    if (spec.state)
        goldens.digest =
            readGoldenDigest((fs::path(folder) / kDigestFileName).string(), script.file);
    return goldens;
}

/// Lines for metric bounds the run broke.
void checkMetrics(const CaptureSpec& spec, const CapturedRun& run, CaptureResult& result) {
    const long long last = run.frames.empty() ? 0 : run.frames.back().frame;
    const auto check = [&](const char* name, const std::optional<double>& bound, double value,
                           const char* unit) {
        if (bound && !(value <= *bound)) {
            result.lines.push_back(spec.name + ": metrics: " + name + " " + shortNumber(value) +
                                   unit + " over frames 0-" + std::to_string(last) +
                                   " exceeds its bound " + shortNumber(*bound) + unit);
        }
    };
    check("max_joint_error", spec.metrics.maxJointError, run.metrics.maxJointError, " m");
    check("energy_drift", spec.metrics.energyDrift, run.metrics.energyDrift, "");
    check("penetration", spec.metrics.penetration, run.metrics.penetration, " m");
}

std::string stateLine(const CaptureSpec& spec, long long frame, const StateComparison& state) {
    const std::string head = spec.name + " frame " + std::to_string(frame) + ": state: ";
    if (!state.structure.empty()) return head + state.structure;
    const StateDifference& worst = state.worst;
    return head + std::to_string(state.outOfTolerance) + " of " + std::to_string(state.compared) +
           " values out of tolerance; worst " + worst.what + ": golden " +
           shortNumber(worst.golden) + ", new " + shortNumber(worst.fresh) + " (differs by " +
           shortNumber(worst.fresh - worst.golden) + ", allowed " + shortNumber(worst.allowed) +
           ")";
}

std::string imageLine(const CaptureSpec& spec, long long frame, const ImageComparison& image,
                      const render::Image& golden, const render::Image& fresh) {
    const std::string head = spec.name + " frame " + std::to_string(frame) + ": image: ";
    if (image.sizeDiffers) {
        return head + std::to_string(fresh.width) + "x" + std::to_string(fresh.height) +
               ", the golden " + std::to_string(golden.width) + "x" + std::to_string(golden.height);
    }
    return head + std::to_string(image.differing) + " of " + std::to_string(image.pixels) +
           " pixels (" + percent(image.fraction()) + ") differ by more than " +
           std::to_string(spec.image->pixelTolerance) + " (allowed " +
           percent(spec.image->maxFraction) + "); largest channel difference " +
           std::to_string(image.largest);
}

/// Compares a run with its goldens.
void compareRun(const CaptureSpec& spec, const CapturedRun& run, const Goldens& goldens,
                CaptureResult& result) {
    bool stateDiffers = false;
    for (const CapturedFrame& captured : run.frames) {
        FrameMismatch mismatch{.frame = captured.frame};
        if (captured.state) {
            StateComparison state =
                compareStates(goldens.states.at(captured.frame), *captured.state, *spec.state);
            if (!state.matches()) {
                result.lines.push_back(stateLine(spec, captured.frame, state));
                mismatch.state = std::move(state);
                stateDiffers = true;
            }
        }
        if (captured.image) {
            const render::Image& golden = goldens.images.at(captured.frame);
            const ImageComparison image =
                compareImages(golden, *captured.image, spec.image->pixelTolerance);
            if (image.sizeDiffers || image.fraction() > spec.image->maxFraction) {
                result.lines.push_back(
                    imageLine(spec, captured.frame, image, golden, *captured.image));
                mismatch.image = image;
                mismatch.pixelTolerance = spec.image->pixelTolerance;
                mismatch.maxFraction = spec.image->maxFraction;
                mismatch.golden = golden;
                mismatch.fresh = *captured.image;
            }
        }
        if (mismatch.state || mismatch.image) result.frames.push_back(std::move(mismatch));
    }
    // With exact tolerances the digest must match too: it sees every frame, not only the listed
    // ones. Its line is news only when no listed frame already differs.
    if (spec.state && spec.state->exact() && !stateDiffers && !run.nonFinite &&
        run.digest != goldens.digest) {
        std::string golden = goldens.digest;
        std::string fresh = run.digest;
        if (!golden.empty()) golden.pop_back();
        if (!fresh.empty()) fresh.pop_back();
        result.lines.push_back(spec.name +
                               ": digest: the run differs between the listed frames (golden " +
                               golden + ", new " + fresh + ")");
    }
}

/// Writes a capture's goldens; prints and counts what changed.
void updateGoldens(const CaptureScript& script, const CaptureSpec& spec, const CapturedRun& run,
                   std::map<GoldenChange, int>& changes, int& removed) {
    const std::string folder = captureFolder(script.goldenFolder, spec.name);
    std::vector<std::pair<std::string, std::string>> files;  // name, bytes
    for (const CapturedFrame& captured : run.frames) {
        if (captured.state)
            files.emplace_back(stateFileName(captured.frame), formatStateFile(*captured.state));
        if (captured.image)
            files.emplace_back(imageFileName(captured.frame), render::encodePng(*captured.image));
    }
    if (spec.state) files.emplace_back(kDigestFileName, run.digest);
    std::vector<std::string> keep;
    for (const auto& [name, bytes] : files) {
        const std::string path = (fs::path(folder) / name).string();
        const GoldenChange change = writeGolden(path, bytes);
        ++changes[change];
        if (change != GoldenChange::Unchanged)
            std::printf("%-9s %s\n", goldenChangeName(change), path.c_str());
        keep.push_back(name);
    }
    for (const std::string& path : removeStaleGoldens(folder, keep)) {
        std::printf("%-9s %s\n", "removed", path.c_str());
        ++removed;
    }
}

int runCaptures(const CaptureOptions& options) {
    // Everything that can be bad input is checked before any output: the script, the names,
    // the goldens (when comparing) and every capture's scene and knobs.
    const CaptureScript script = parseCaptureScript(options.script);
    const std::vector<const CaptureSpec*> selected = selectCaptures(script, options.only);
    std::map<std::string, Goldens> goldens;
    if (!options.update) {
        for (const CaptureSpec* spec : selected)
            goldens[spec->name] = readGoldens(script, *spec);
    }
    std::vector<std::unique_ptr<CaptureScene>> scenes;
    bool anyImage = false;
    for (const CaptureSpec* spec : selected) {
        scenes.push_back(std::make_unique<CaptureScene>(*spec, script.file));
        anyImage = anyImage || spec->image.has_value();
    }
    std::unique_ptr<FrameRenderer> renderer;
    if (anyImage) renderer = std::make_unique<FrameRenderer>();
    if (!options.reportDirectory.empty()) prepareReportFolder(options.reportDirectory);

    std::vector<CaptureResult> results;
    for (const CaptureSpec& spec : script.captures)
        results.push_back({.name = spec.name, .scene = spec.scene});
    std::map<GoldenChange, int> changes;
    int removed = 0;
    long long framesCaptured = 0;
    const InterruptGuard interruptGuard;
    ProgressLine progress;
    for (std::size_t i = 0; i < selected.size(); ++i) {
        const CaptureSpec& spec = *selected[i];
        CaptureResult& result = results[static_cast<std::size_t>(&spec - script.captures.data())];
        result.checked = true;
        const CapturedRun run = runCapture(*scenes[i], spec, renderer.get(), [&](long long frame) {
            progress.show(i + 1, selected.size(), spec.name, frame, spec.frames.back());
        });
        scenes[i].reset();  // its world is not needed any more
        if (run.interrupted != 0) {
            progress.clear();
            std::fprintf(stderr, "substep capture: interrupted\n");
            return 128 + run.interrupted;
        }
        framesCaptured += static_cast<long long>(run.frames.size());
        if (run.nonFinite) {
            result.lines.push_back(spec.name + " frame " + std::to_string(*run.nonFinite) +
                                   ": the state turned non-finite");
        }
        checkMetrics(spec, run, result);
        if (options.update) {
            // Goldens of an unsound run (non-finite, outside its metric bounds) are not written.
            if (result.matches()) updateGoldens(script, spec, run, changes, removed);
        } else if (!run.nonFinite) {
            compareRun(spec, run, goldens.at(spec.name), result);
        }
        progress.clear();
        for (const std::string& line : result.lines)
            std::printf("%s\n", line.c_str());
        std::fflush(stdout);
    }
    progress.clear();

    if (options.update && options.only.empty()) {
        // Folders of captures the script no longer has.
        std::error_code error;
        if (fs::is_directory(script.goldenFolder, error)) {
            for (const fs::directory_entry& entry :
                 fs::directory_iterator(script.goldenFolder, error)) {
                const std::string name = entry.path().filename().string();
                const bool listed =
                    std::any_of(script.captures.begin(), script.captures.end(),
                                [&](const CaptureSpec& spec) { return spec.name == name; });
                if (!entry.is_directory() || listed) continue;
                for (const std::string& path : removeStaleGoldens(entry.path().string(), {})) {
                    std::printf("%-9s %s\n", "removed", path.c_str());
                    ++removed;
                }
                fs::remove(entry.path(), error);  // only when now empty
            }
        }
    }

    if (!options.reportDirectory.empty())
        writeCaptureReport(options.reportDirectory, script.file, results);

    std::size_t differing = 0;
    for (const CaptureResult& result : results)
        differing += result.checked && !result.matches() ? 1 : 0;
    const std::string captures =
        std::to_string(selected.size()) + " capture" + (selected.size() == 1 ? "" : "s");
    if (options.update) {
        std::printf(
            "substep capture %s: goldens of %s: %d added, %d changed, %d unchanged, %d removed\n",
            script.file.c_str(), captures.c_str(), changes[GoldenChange::Added],
            changes[GoldenChange::Changed], changes[GoldenChange::Unchanged], removed);
        if (differing > 0) {
            std::printf("%zu capture%s not updated (see above)\n", differing,
                        differing == 1 ? "" : "s");
        }
    } else if (differing == 0) {
        std::printf("substep capture %s: %s match%s (%lld frames)\n", script.file.c_str(),
                    captures.c_str(), selected.size() == 1 ? "es" : "", framesCaptured);
    } else {
        std::printf("substep capture %s: %zu of %s differ\n", script.file.c_str(), differing,
                    captures.c_str());
    }
    if (!options.reportDirectory.empty()) {
        std::printf("report: %s\n", (fs::path(options.reportDirectory) / "index.html").c_str());
    }
    return differing == 0 ? 0 : 1;
}

}  // namespace

CLI::App* addCaptureCommand(CLI::App& app, CaptureOptions& options) {
    CLI::App* command = app.add_subcommand(
        "capture", "Scripted regression captures against stored goldens (state, images, metrics)");
    command
        ->add_option("SCRIPT", options.script,
                     "A capture script (.json); goldens in SCRIPT.golden/ beside it")
        ->required();
    command->add_flag("--update", options.update,
                      "Write the goldens from this build instead of comparing");
    command
        ->add_option("--report", options.reportDirectory,
                     "Write DIR/index.html: golden, new and difference images, state tables")
        ->type_name("DIR");
    command
        ->add_option("--only", options.only,
                     "Run only the captures named (repeatable, or several names)")
        ->type_name("NAME");
    return command;
}

int captureCommand(const CaptureOptions& options) {
    return runReportingErrors("capture", [&] { return runCaptures(options); });
}

}  // namespace substep
