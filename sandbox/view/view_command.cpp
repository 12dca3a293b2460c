#include "view/view_command.h"

#include "atomic_file.h"
#include "command_options.h"
#include "render_command.h"
#include "scene_source.h"
#include "scenes/scene_registry.h"
#include "view/view_app.h"
#include "view/view_controls.h"

#include "render/png_codec.h"

#include <cstdio>
#include <cstdlib>
#include <memory>

namespace substep::view {

namespace {

/// Debian's GLFW is built for X11, so an X display is what a window needs (XWayland gives one).
bool hasDisplay() {
    const char* display = std::getenv("DISPLAY");
    return display != nullptr && display[0] != '\0';
}

int runView(const ViewOptions& options) {
    // Every input is checked before the window opens or any output exists.
    const auto [width, height] = parseImageSize(options.size);
    if (!options.screenshot.empty() && options.frames == 0) {
        throw UsageError("--screenshot: needs --frames N, the frame whose window is saved");
    }
    std::optional<CompareSplits> compare;
    if (options.compare) {
        compare = options.compare->empty() ? kPaperCompareSplits : parseCompareSplits(*options.compare);
        if (!compare) {
            throw UsageError("--compare: expected SUBSTEPSxITERATIONS,SUBSTEPSxITERATIONS with counts from 1 to 1000, "
                             "each optionally :paper or :start, e.g. 20x1,1x20 or "
                             "20x1:paper,20x1:start; got '" + *options.compare + "'");
        }
    }
    std::optional<render::QualityLevel> quality;
    if (!options.quality.empty()) {
        render::QualityLevel level{};
        if (!render::parseQualityLevel(options.quality, level)) {
            throw UsageError("--quality: expected light, medium or full; got '" + options.quality + "'");
        }
        quality = level;
    }
    SceneSource source = resolveScene(options.scene.empty() ? defaultViewScene() : options.scene);
    if (!hasDisplay()) {
        std::fprintf(stderr,
                     "substep: no display ($DISPLAY is unset); use `substep render SCENE --frames LIST "
                     "--out DIR` to render PNGs headless\n"
                     "  (or `substep run SCENE` to simulate headless and print a summary)\n");
        return 2;
    }
    // Opened before the window, so a screenshot path that cannot be written fails before any
    // simulation runs; committed only once the frame exists.
    std::unique_ptr<AtomicFile> screenshot;
    if (!options.screenshot.empty()) screenshot = std::make_unique<AtomicFile>(options.screenshot);

    ViewAppOptions appOptions;
    appOptions.width = width;
    appOptions.height = height;
    appOptions.frames = options.frames;
    appOptions.captureLastFrame = screenshot != nullptr;
    appOptions.compare = compare;
    appOptions.quality = quality;
    appOptions.hidePanel = options.hidePanel;
    const std::string label = source.label;
    const ViewAppResult result = runViewApp(std::move(source), appOptions);

    if (screenshot) {
        if (!result.lastFrame) throw OutputError("--screenshot " + options.screenshot + ": the window had no pixels to save");
        screenshot->write(render::encodePng(*result.lastFrame));
        screenshot->commit();
        std::printf("saved %s after %lld frame%s of %s (%dx%d)\n", options.screenshot.c_str(), options.frames,
                    options.frames == 1 ? "" : "s", label.c_str(), result.lastFrame->width, result.lastFrame->height);
    }
    if (options.frames > 0) {
        const ViewFrameTiming& timing = result.timing;
        std::printf("frames: %.2f ms median (%.1f fps) over %lld frames: physics %.2f, draw %.2f, swap %.2f ms; "
                    "drawing's CPU %.2f ms (all threads); quality %s on %s\n",
                    timing.frameMs, timing.frameMs > 0.0 ? 1000.0 / timing.frameMs : 0.0, timing.frames,
                    timing.physicsMs, timing.renderMs, timing.swapMs, timing.renderCpuMs,
                    render::qualityName(timing.quality), timing.glRenderer.c_str());
    }
    if (!result.finite) {
        std::fprintf(stderr, "substep view: the state of %s turned non-finite\n", label.c_str());
        return options.frames > 0 ? 1 : 0;
    }
    return 0;
}

}  // namespace

std::string defaultViewScene() {
    if (findBuiltinScene("boxes3") != nullptr) return "boxes3";
    return std::string(builtinScenes().front().name);
}

CLI::App* addViewCommand(CLI::App& app, ViewOptions& options) {
    CLI::App* command = app.add_subcommand("view", "Interactive window (the default command)");
    command->add_option("SCENE", options.scene, "A built-in scene name or a .json scene file (default boxes3)");
    command->add_option("--frames", options.frames, "Run N frames without waiting for real time, then exit")
        ->type_name("N")
        ->check(CLI::Range(1LL, kMaxRenderFrame));
    command->add_option("--screenshot", options.screenshot, "Save the window's last frame as a PNG (needs --frames)")
        ->type_name("F.png");
    command
        ->add_option("--compare", options.compare,
                     "Run the scene twice side by side with these solver settings (default 20x1,1x20, the "
                     "paper's Fig. 10; SxI:start uses the start-direction joint projection)")
        ->expected(0, 1)
        ->type_name("SxI,SxI");
    command->add_option("--size", options.size, "Window size in pixels (default 1280x720)")->type_name("WxH");
    command
        ->add_option("--quality", options.quality,
                     "Rendering quality: light, medium or full (default: light on a software rasteriser such as "
                     "llvmpipe, else full; the panel switches it)")
        ->type_name("LEVEL");
    command->add_flag("--hide-panel", options.hidePanel, "Start with the panel hidden (Tab shows it)");
    command->footer(controlsHelpText());
    return command;
}

int viewCommand(const ViewOptions& options) {
    return runReportingErrors("view", [&] { return runView(options); });
}

}  // namespace substep::view
