#include "sweep_command.h"

#include "atomic_file.h"
#include "command_options.h"
#include "csv_writer.h"
#include "error_measures.h"
#include "output_transaction.h"
#include "scene_source.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string_view>
#include <utility>
#include <vector>

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace substep {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

/// Accepted ranges of one split (DESIGN.md).
constexpr int kMaxSubsteps = 10000;
constexpr int kMaxIterations = 1000;
constexpr long long kMaxFrames = 10'000'000;
constexpr double kDefaultSeconds = 5.0;
/// The plotter's exit code for "matplotlib is not installed" (tools/plot_style.py).
constexpr int kPlotterMissingMatplotlib = 3;

// --- Options -----------------------------------------------------------------------------------

/// The budgets to sweep, ascending, without repeats (--budget and --budgets are one set).
std::vector<int> parseBudgets(const SweepOptions& options) {
    if (options.budget.empty() && options.budgets.empty()) {
        throw UsageError("give a budget: --budget B or --budgets B1,B2,...");
    }
    std::vector<int> budgets;
    if (!options.budget.empty()) {
        budgets.push_back(
            static_cast<int>(parseInteger("--budget", options.budget, 1, kMaxBudget)));
    }
    // --budgets: comma-separated; an empty piece ("10,,20", "10,") is an error like any other.
    if (!options.budgets.empty()) {
        const std::string_view list = options.budgets;
        for (std::size_t start = 0;;) {
            const std::size_t comma = list.find(',', start);
            if (comma == start || start == list.size()) {
                throw UsageError("--budgets: expected whole numbers separated by commas, got '" +
                                 options.budgets + "'");
            }
            budgets.push_back(static_cast<int>(
                parseInteger("--budgets", list.substr(start, comma - start), 1, kMaxBudget)));
            if (comma == std::string_view::npos) break;
            start = comma + 1;
        }
    }
    std::sort(budgets.begin(), budgets.end());
    budgets.erase(std::unique(budgets.begin(), budgets.end()), budgets.end());
    return budgets;
}

struct Split {
    int budget = 0;
    int substeps = 0;
    int iterations = 0;
};

/// Every split of the budgets, substeps x iterations = budget, from B x 1 down to 1 x B. Splits
/// with more iterations than accepted are left out, with a note.
std::vector<Split> allSplits(const std::vector<int>& budgets) {
    std::vector<Split> splits;
    for (const int budget : budgets) {
        int skipped = 0;
        for (int substeps = budget; substeps >= 1; --substeps) {
            if (budget % substeps != 0) continue;
            const int iterations = budget / substeps;
            if (substeps > kMaxSubsteps || iterations > kMaxIterations) {
                ++skipped;
                continue;
            }
            splits.push_back({budget, substeps, iterations});
        }
        if (skipped > 0) {
            std::fprintf(stderr,
                         "substep sweep: budget %d: leaving out %d split%s with more than %d "
                         "iterations\n",
                         budget, skipped, skipped == 1 ? "" : "s", kMaxIterations);
        }
    }
    return splits;
}

// --- Progress ----------------------------------------------------------------------------------

/// Progress on stderr: a bar redrawn in place when stderr is a terminal, otherwise one line per
/// finished split (logs stay readable). Work is counted as frames x budget, which is what a
/// split costs to first order.
class Progress {
  public:
    Progress(std::string scene, const std::vector<Split>& splits, long long frames)
        : scene_(std::move(scene)),
          splitCount_(splits.size()),
          frames_(frames),
          terminal_(::isatty(STDERR_FILENO) == 1) {
        for (const Split& split : splits)
            total_ += static_cast<double>(split.budget) * frames;
    }
    ~Progress() { clear(); }
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;

    void startSplit(std::size_t index, const Split& split) {
        index_ = index;
        split_ = split;
        draw(0, true);
    }
    /// Called after every frame; redraws at most ten times a second.
    void frame(long long frame) {
        if (terminal_) draw(frame, false);
    }
    void endSplit(double msPerFrame) {
        done_ += static_cast<double>(split_.budget) * frames_;
        if (!terminal_) {
            std::fprintf(stderr, "substep sweep: %s %zu/%zu budget %d split %dx%d: %.4g ms/frame\n",
                         scene_.c_str(), index_ + 1, splitCount_, split_.budget, split_.substeps,
                         split_.iterations, msPerFrame);
        }
    }
    /// Erases the bar, so what follows starts on a clean line.
    void clear() {
        if (terminal_ && drawn_) std::fprintf(stderr, "\r\033[K");
        drawn_ = false;
    }

  private:
    void draw(long long frame, bool force) {
        if (!terminal_) return;
        const Clock::time_point now = Clock::now();
        if (!force && now - lastDraw_ < std::chrono::milliseconds(100)) return;
        lastDraw_ = now;
        const double fraction =
            total_ > 0.0 ? (done_ + static_cast<double>(split_.budget) * frame) / total_ : 1.0;
        constexpr int kWidth = 30;
        const int filled = std::clamp(static_cast<int>(fraction * kWidth), 0, kWidth);
        std::fprintf(stderr, "\r\033[Ksweep %s [%.*s%.*s] %3d%%  budget %d  %dx%d  (%zu/%zu)",
                     scene_.c_str(), filled, "##############################", kWidth - filled,
                     "..............................", static_cast<int>(fraction * 100.0),
                     split_.budget, split_.substeps, split_.iterations, index_ + 1, splitCount_);
        std::fflush(stderr);
        drawn_ = true;
    }

    std::string scene_;
    std::size_t splitCount_ = 0;
    long long frames_ = 0;
    bool terminal_ = false;
    double total_ = 0.0;
    double done_ = 0.0;
    std::size_t index_ = 0;
    Split split_;
    Clock::time_point lastDraw_{};
    bool drawn_ = false;
};

// --- One split ---------------------------------------------------------------------------------

struct SplitResult {
    Split split;
    double msPerFrame = 0.0;  ///< median over frames of the time inside world.step
    ErrorMeasures measures;
    bool finite = true;
};

/// Thrown out of the frame loop on Ctrl-C; carries the signal.
struct Interrupted {
    int signal = 0;
};

SplitResult runSplit(const SceneSource& source, const SceneEntry* entry, const Split& split,
                     long long frames, int threads, Progress& progress) {
    SceneDescription description = source.description;  // --joint-projection, --restitution applied
    description.substeps = split.substeps;
    description.iterations = split.iterations;
    LiveScene live = startLabelledScene(source, description);
    if (threads != 1) {
        ecs::PhysicsSystem physics = live.physics();
        WorldSettings threaded = physics.settings();
        threaded.threads = threads;
        physics.setSettings(threaded);
    }
    SceneInstance& scene = live.instance();
    const World& world = live.world();
    ErrorRecorder recorder(scene, errorReference(entry, scene));
    recorder.sample();

    SplitResult result{.split = split};
    std::vector<double> frameMs;
    frameMs.reserve(static_cast<std::size_t>(frames));
    for (long long frame = 1; frame <= frames; ++frame) {
        if (const int signal = interruptSignal(); signal != 0) throw Interrupted{signal};
        frameMs.push_back(std::chrono::duration<double, std::milli>(live.step()).count());
        recorder.sample();
        progress.frame(frame);
        if (!world.isFinite()) {
            result.finite = false;
            break;
        }
    }
    // The median, not the mean: a frame the machine preempted says nothing about the solver.
    const auto middle = frameMs.begin() + static_cast<std::ptrdiff_t>(frameMs.size() / 2);
    std::nth_element(frameMs.begin(), middle, frameMs.end());
    result.msPerFrame = *middle;

    result.measures = recorder.measures();
    if (!result.finite) {
        // Unbounded error: whatever was measured before the blow-up would flatter the split.
        ErrorMeasures& m = result.measures;
        m.energyDrift = m.energyErrorFinal = m.maxJointError = m.meanJointError = INFINITY;
        if (m.chainElongation) m.chainElongation = INFINITY;
    }
    return result;
}

// --- Outputs -----------------------------------------------------------------------------------

std::string sweepCsv(const std::vector<SplitResult>& results) {
    std::string text = kSweepCsvHeader;
    text += '\n';
    for (const SplitResult& r : results) {
        appendInteger(text, r.split.budget);
        text += ',';
        appendInteger(text, r.split.substeps);
        text += ',';
        appendInteger(text, r.split.iterations);
        const ErrorMeasures& m = r.measures;
        for (const double value :
             {r.msPerFrame, m.energyDrift, m.energyErrorFinal, m.maxJointError, m.meanJointError}) {
            text += ',';
            appendNumber(text, value);
        }
        text += ',';  // chain_elongation: blank for a scene without a chain measure
        if (m.chainElongation) appendNumber(text, *m.chainElongation);
        text += ',';
        appendNumber(text, m.penetration);
        text += '\n';
    }
    return text;
}

void printTable(const SceneSource& source, const std::vector<SplitResult>& results,
                long long frames, double dt) {
    std::printf("scene  %s%s, %lld frames of %.6g s = %.6g s per split\n", source.label.c_str(),
                source.builtin ? " (built-in)" : "", frames, dt, static_cast<double>(frames) * dt);
    std::printf("ms/frame: median over frames of the time inside world.step\n\n");
    std::printf("%6s %11s %10s %12s %12s %12s %12s %12s\n", "budget", "split", "ms/frame",
                "energy_drift", "energy_final", "max_joint_m", "mean_joint_m", "elongation");
    for (const SplitResult& r : results) {
        const ErrorMeasures& m = r.measures;
        char split[32];
        std::snprintf(split, sizeof(split), "%dx%d", r.split.substeps, r.split.iterations);
        char elongation[32] = "-";
        if (m.chainElongation)
            std::snprintf(elongation, sizeof(elongation), "%.4g", *m.chainElongation);
        std::printf("%6d %11s %10.4g %12.4g %12.4g %12.4g %12.4g %12s\n", r.split.budget, split,
                    r.msPerFrame, m.energyDrift, m.energyErrorFinal, m.maxJointError,
                    m.meanJointError, elongation);
    }
}

// --- The plotter -------------------------------------------------------------------------------

std::string pythonPath() {
    const char* custom = std::getenv("SUBSTEP_PYTHON");
    return custom != nullptr && *custom != '\0' ? custom : "/usr/bin/python3";
}

/// tools/plot_sweep.py in the source tree this program was built from, else next to the
/// program (an installed or copied build, with plot_style.py beside it). Empty when neither
/// exists.
std::string findPlotScript() {
    std::vector<fs::path> candidates;
#ifdef SUBSTEP_SOURCE_DIR
    candidates.push_back(fs::path(SUBSTEP_SOURCE_DIR) / "tools" / "plot_sweep.py");
#endif
    std::error_code error;
    const fs::path executable = fs::read_symlink("/proc/self/exe", error);
    if (!error) {
        candidates.push_back(executable.parent_path() / "tools" / "plot_sweep.py");
        candidates.push_back(executable.parent_path() / "plot_sweep.py");
    }
    for (const fs::path& candidate : candidates)
        if (fs::is_regular_file(candidate, error)) return candidate.string();
    return {};
}

/// Runs `python script arguments...` and returns its exit code (-1 when it could not start or
/// died of a signal).
int runPython(const std::string& python, const std::vector<std::string>& arguments) {
    std::vector<char*> argv;
    argv.push_back(const_cast<char*>(python.c_str()));
    for (const std::string& argument : arguments)
        argv.push_back(const_cast<char*>(argument.c_str()));
    argv.push_back(nullptr);
    pid_t pid = 0;
    if (::posix_spawn(&pid, python.c_str(), nullptr, nullptr, argv.data(), environ) != 0) return -1;
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0) {
        if (errno != EINTR) return -1;
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/// Why a plot cannot be drawn here, or nothing when it can. Checked before the sweep, so a long
/// run does not end in a surprise; the message says what to install.
std::optional<std::string> plotterProblem(const std::string& python, const std::string& script) {
    if (::access(python.c_str(), X_OK) != 0) {
        return python +
               " not found: plots need Python 3 with matplotlib (apt-get install "
               "python3-matplotlib, or tools/install-deps.sh)";
    }
    if (script.empty()) {
        return "tools/plot_sweep.py not found (looked in the source tree and next to the program)";
    }
    const int status = runPython(python, {script, "--check"});
    if (status == kPlotterMissingMatplotlib) {
        return "matplotlib is not installed for " + python +
               ": apt-get install python3-matplotlib (or tools/install-deps.sh)";
    }
    if (status != 0) return script + " --check failed (exit " + std::to_string(status) + ")";
    return std::nullopt;
}

/// A file under the temporary directory, removed when this goes away (the plotter's input when
/// no --csv is kept).
class TemporaryFile {
  public:
    explicit TemporaryFile(const std::string& contents) {
        std::string pattern = (fs::temp_directory_path() / "substep-sweep-XXXXXX.csv").string();
        const int descriptor = ::mkstemps(pattern.data(), 4);
        if (descriptor < 0) throw OutputError(pattern + ": cannot create a temporary file");
        path_ = pattern;
        const bool written = ::write(descriptor, contents.data(), contents.size()) ==
                             static_cast<ssize_t>(contents.size());
        ::close(descriptor);
        if (!written) throw OutputError(path_ + ": cannot write a temporary file");
    }
    ~TemporaryFile() {
        if (!path_.empty()) ::unlink(path_.c_str());
    }
    TemporaryFile(const TemporaryFile&) = delete;
    TemporaryFile& operator=(const TemporaryFile&) = delete;
    const std::string& path() const { return path_; }

  private:
    std::string path_;
};

// --- The command -------------------------------------------------------------------------------

int sweep(const SweepOptions& options) {
    // Check every input before any output exists: a bad option or scene leaves no file behind.
    const std::vector<int> budgets = parseBudgets(options);
    const int threads = parseThreads(options.threads);
    const double seconds =
        options.seconds.empty() ? kDefaultSeconds : parsePositiveReal("--seconds", options.seconds);
    const std::optional<JointProjection> projection =
        options.jointProjection.empty()
            ? std::nullopt
            : std::optional(parseJointProjection("--joint-projection", options.jointProjection));
    SceneSource source = resolveScene(options.scene);
    if (projection) source.description.jointProjection = *projection;
    if (!options.restitution.empty())
        source.description.sweptRestitution = parseSweptRestitution("--restitution", options.restitution);
    const SceneEntry* entry = source.builtin ? findBuiltinScene(source.label) : nullptr;
    const double dt = source.description.dt;
    const long long frames = framesForSeconds(seconds, dt, kMaxFrames);
    if (frames < 1) {
        throw UsageError("--seconds: " + options.seconds +
                         " s is less than half a frame (dt = " + std::to_string(dt) + " s)");
    }
    const std::vector<Split> splits = allSplits(budgets);
    if (splits.empty()) throw UsageError("no split of the budget is within the accepted ranges");

    // Outputs are opened now (a missing folder fails before the sweep, not after it) and appear
    // only once everything is measured.
    OutputTransaction outputs(source.builtin ? std::vector<std::string>{}
                                             : std::vector<std::string>{options.scene});
    AtomicFile* csvFile = options.csvPath.empty() ? nullptr : &outputs.add("--csv", options.csvPath);
    AtomicFile* plotFile = options.plotPath.empty() ? nullptr : &outputs.add("--plot", options.plotPath);
    const std::string python = pythonPath();
    const std::string script = plotFile ? findPlotScript() : std::string();
    std::optional<std::string> plotProblem;
    if (plotFile) {
        plotProblem = plotterProblem(python, script);
        if (plotProblem) {
            std::fprintf(stderr, "substep sweep: cannot plot: %s; sweeping anyway, no plot\n",
                         plotProblem->c_str());
        }
    }

    // The sweep: each split from a fresh build of the scene with its own settings.
    std::vector<SplitResult> results;
    {
        // Ctrl-C ends a long sweep cleanly: the loop notices, and the temporary outputs are
        // removed.
        const InterruptGuard interruptGuard;
        Progress progress(source.label, splits, frames);
        for (std::size_t i = 0; i < splits.size(); ++i) {
            progress.startSplit(i, splits[i]);
            try {
                results.push_back(runSplit(source, entry, splits[i], frames, threads, progress));
            } catch (const Interrupted& interrupted) {
                progress.clear();
                std::fprintf(stderr, "substep sweep: interrupted; no output written\n");
                return 128 + interrupted.signal;
            }
            progress.endSplit(results.back().msPerFrame);
        }
    }

    // Outputs: the CSV whole, then the plot drawn from its temporary file; both appear together
    // at the end (the CSV alone when there is no plotter, as documented).
    const std::string csv = sweepCsv(results);
    if (csvFile) {
        csvFile->write(csv);
        csvFile->finish();
    }
    printTable(source, results, frames, dt);

    int exitCode = 0;
    if (plotFile && plotProblem) {
        plotFile->discard();
        std::fprintf(stderr, "substep sweep: no plot written: %s\n", plotProblem->c_str());
        exitCode = 2;
    } else if (plotFile) {
        // The plotter writes the PNG over plotFile's temporary file, which commit() then renames
        // into place: the target is whole or untouched.
        std::optional<TemporaryFile> input;
        if (!csvFile) input.emplace(csv);
        const std::string csvPath = csvFile ? csvFile->temporaryPath() : input->path();
        char title[256];
        std::snprintf(title, sizeof(title), "substep sweep %s, %.6g s per split",
                      source.label.c_str(), static_cast<double>(frames) * dt);
        const int status =
            runPython(python, {script, csvPath, plotFile->temporaryPath(), "--title", title});
        if (status != 0) {
            plotFile->discard();
            std::fprintf(stderr, "substep sweep: %s failed (exit %d); no plot written\n",
                         script.c_str(), status);
            exitCode = 2;
        }
    }
    outputs.commit();

    std::size_t nonFinite = 0;
    for (const SplitResult& r : results) {
        if (r.finite) continue;
        ++nonFinite;
        std::fprintf(stderr, "substep sweep: split %dx%d turned non-finite; its measures are inf\n",
                     r.split.substeps, r.split.iterations);
    }
    if (exitCode == 0 && nonFinite > 0) exitCode = 1;
    return exitCode;
}

}  // namespace

CLI::App* addSweepCommand(CLI::App& app, SweepOptions& options) {
    CLI::App* command = app.add_subcommand(
        "sweep", "Error against run time at fixed budgets (substeps x iterations)");
    command->add_option("SCENE", options.scene, "A built-in scene name or a .json scene file")
        ->required();
    command->add_option("--budget", options.budget, "Budget B = substeps x iterations (1-10000)")
        ->type_name("B");
    command->add_option("--budgets", options.budgets, "Several budgets, e.g. 10,20,40,80")
        ->type_name("LIST");
    command->add_option("--seconds", options.seconds, "Simulated time per split (default 5)")
        ->type_name("T");
    command->add_option("--csv", options.csvPath, "Write one row per split")->type_name("F");
    command->add_option("--plot", options.plotPath, "Draw error against ms/frame to a PNG")
        ->type_name("F.png");
    command->add_option("--threads", options.threads, "Threads the step uses (default 1; 1-64)")
        ->type_name("N");
    command->add_option("--joint-projection", options.jointProjection,
                        "Joint directions: paper (current state) or start (substep start)")
        ->type_name("paper|start");
    command->add_option("--restitution", options.restitution,
                        "Restitution: swept (two-body collisions, any order) or paper (Eq. 34 alone)")
        ->type_name("swept|paper");
    command->footer(
        "Every split substeps x iterations = B runs from a fresh build of the scene. ms/frame is "
        "the median over frames of the time inside world.step. Plots need /usr/bin/python3 "
        "with matplotlib (tools/plot_sweep.py).");
    return command;
}

int sweepCommand(const SweepOptions& options) {
    return runReportingErrors("sweep", [&] { return sweep(options); });
}

}  // namespace substep
