#pragma once
/// `substep view [SCENE] [--compare [SxI,SxI]] [--frames N --screenshot F.png] [--size WxH]
/// [--quality light|medium|full] [--hide-panel]` and
/// `substep` alone: the interactive window (DESIGN.md's command contract). --compare opens it in
/// compare mode (compare_session.h). Without a display it says so, points to
/// `substep render`, and exits 2. With --frames it runs N frames as fast as it can (one scene dt
/// each, no waiting for real time), optionally saves the window as a PNG, and exits: the
/// scripted form the tests run under Xvfb; it then prints the frames' median times (the buffer
/// swap included), what docs/PERFORMANCE_LOG.md records. `view --help` lists the window's keys.

#include <CLI/CLI.hpp>

#include <optional>
#include <string>

namespace substep::view {

/// The options as typed; checked by viewCommand.
struct ViewOptions {
    std::string scene;  ///< empty: the default scene (boxes3, else the first built-in)
    long long frames = 0;  ///< 0: interactive, until the window is closed
    std::string screenshot;
    std::string size = "1280x720";
    /// Set: compare mode, with "SUBSTEPSxITERATIONS,SUBSTEPSxITERATIONS" or, empty, the paper's
    /// 20x1,1x20.
    std::optional<std::string> compare;
    /// "light", "medium" or "full" (render_quality.h); empty: chosen from the GL renderer.
    std::string quality;
    bool hidePanel = false;  ///< start with the UI hidden (Tab shows it)
};

/// The scene `substep` alone opens.
std::string defaultViewScene();

/// Declares `view` and its options on `app`, bound to `options`.
CLI::App* addViewCommand(CLI::App& app, ViewOptions& options);

/// Runs the viewer. Returns the exit code: 0 closed (or the scripted frames done), 1 the state
/// turned non-finite in a scripted run, 2 no display, bad input, or an unwritable screenshot.
int viewCommand(const ViewOptions& options);

}  // namespace substep::view
