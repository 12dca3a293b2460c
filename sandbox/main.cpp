// substep: the Substep sandbox's command line (DESIGN.md, "The `substep` command"). It reads top
// to bottom: declare the commands, parse, dispatch. Each command lives in its own file pair
// (run_command.h, ...).

#include "atomic_file.h"
#include "bench_command.h"
#include "capture/capture_command.h"
#include "render_command.h"
#include "run_command.h"
#include "scenes/scene_registry.h"
#include "sweep_command.h"
#include "view/view_command.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <string>
#include <string_view>

namespace {

/// `substep scenes`: one line per built-in scene, names padded into a column.
int listScenes() {
    std::size_t width = 0;
    for (const substep::SceneEntry& entry : substep::builtinScenes()) {
        width = std::max(width, entry.name.size());
    }
    for (const substep::SceneEntry& entry : substep::builtinScenes()) {
        std::printf("%-*.*s  %.*s\n", static_cast<int>(width), static_cast<int>(entry.name.size()),
                    entry.name.data(), static_cast<int>(entry.description.size()),
                    entry.description.data());
    }
    return 0;
}

/// The first option of the given command that was given an empty value (`--csv ''`), or null.
/// An empty value is never meaningful: it would read as "not given" and be silently ignored.
const CLI::Option* emptyValuedOption(const CLI::App& command) {
    for (const CLI::Option* option : command.get_options()) {
        if (option->count() == 0 || option->get_expected_min() == 0) continue;  // flags take none
        for (const std::string& value : option->results())
            if (value.empty()) return option;
    }
    return nullptr;
}

}  // namespace

int main(int argc, char** argv) {
    // 1. Declare the commands.
    CLI::App app{"Substep: XPBD rigid bodies, interactive and headless", "substep"};
    app.set_version_flag("--version", SUBSTEP_VERSION);
    app.require_subcommand(0, 1);
    app.footer("Exit codes: 0 success, 1 a check failed (non-finite state, a capture differs), 2 bad input.");

    substep::view::ViewOptions viewOptions;
    substep::view::addViewCommand(app, viewOptions);

    CLI::App* scenesCommand = app.add_subcommand("scenes", "List the built-in scenes");

    substep::RunOptions runOptions;
    CLI::App* runCommand = substep::addRunCommand(app, runOptions);

    substep::BenchOptions benchOptions;
    CLI::App* benchCommand = substep::addBenchCommand(app, benchOptions);

    substep::SweepOptions sweepOptions;
    CLI::App* sweepCommand = substep::addSweepCommand(app, sweepOptions);

    substep::RenderOptions renderOptions;
    CLI::App* renderCommand = substep::addRenderCommand(app, renderOptions);

    substep::CaptureOptions captureOptions;
    CLI::App* captureCommand = substep::addCaptureCommand(app, captureOptions);

    // 2. Parse. CLI11 exits usage errors with codes from 100 up; the contract says 2, and one
    // line naming the command (CLI11's own printout takes two).
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& error) {
        if (error.get_exit_code() == 0) return app.exit(error);  // --help, --version
        // Control characters (a newline in a typed name) are shown escaped.
        std::fprintf(stderr, "substep: %s (substep --help for usage)\n",
                     substep::printableName(error.what()).c_str());
        return 2;
    }
    for (const CLI::App* command : app.get_subcommands()) {
        if (const CLI::Option* option = emptyValuedOption(*command)) {
            std::fprintf(stderr, "substep %s: %s: empty value\n", command->get_name().c_str(),
                         option->get_name().c_str());
            return 2;
        }
    }

    // 3. Dispatch to the one command given; none at all means the viewer.
    if (scenesCommand->parsed()) return listScenes();
    if (runCommand->parsed()) return substep::runCommand(runOptions);
    if (benchCommand->parsed()) return substep::benchCommand(benchOptions);
    if (sweepCommand->parsed()) return substep::sweepCommand(sweepOptions);
    if (renderCommand->parsed()) return substep::renderCommand(renderOptions);
    if (captureCommand->parsed()) return substep::captureCommand(captureOptions);
    return substep::view::viewCommand(viewOptions);  // `view`, or no command at all
}
