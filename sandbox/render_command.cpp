#include "render_command.h"

#include "atomic_file.h"
#include "command_options.h"
#include "knob_settings.h"
#include "output_transaction.h"
#include "scene_drawing.h"
#include "scene_source.h"

#include "render/headless_context.h"
#include "render/offscreen_target.h"
#include "render/png_codec.h"
#include "render/renderer.h"

#include <cstdio>
#include <filesystem>
#include <optional>
#include <set>
#include <string_view>

namespace substep {

namespace {

std::vector<std::string_view> split(std::string_view text, char separator) {
    std::vector<std::string_view> parts;
    std::size_t start = 0;
    while (true) {
        const std::size_t end = text.find(separator, start);
        parts.push_back(text.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start));
        if (end == std::string_view::npos) return parts;
        start = end + 1;
    }
}

/// DIR, created when missing. Throws OutputError naming --out when it is not a usable folder.
std::filesystem::path prepareOutputDirectory(const std::string& directory) {
    namespace fs = std::filesystem;
    std::error_code error;
    fs::create_directories(directory, error);
    if (!fs::is_directory(directory)) {
        throw OutputError("--out " + directory + ": cannot create the folder" +
                          (error ? " (" + error.message() + ")" : " (a file has that name)"));
    }
    return directory;
}

int renderFrames(const RenderOptions& options) {
    // Every input is checked before any output exists or a GL context is made.
    const auto [width, height] = parseImageSize(options.size);
    if (options.frames.empty()) throw UsageError("--frames: required, e.g. --frames 0,40,120");
    const std::vector<long long> frames = parseFrameList(options.frames);
    if (options.outDirectory.empty()) throw UsageError("--out: required, the folder the PNGs go to");
    const SceneSource source = resolveScene(options.scene);
    const SceneDescription& description = source.description;
    LiveScene live = startLabelledScene(source);
    applyKnobSettings(live, parseKnobSettings(options.knobs), source.label);

    const std::unique_ptr<render::GlContext> context = render::createHeadlessContext();
    const render::GlApi gl = context->loadApi();
    render::Renderer renderer(gl);
    std::unique_ptr<render::OffscreenTarget> target;
    try {
        target = std::make_unique<render::OffscreenTarget>(gl, render::PixelSize{width, height});
    } catch (const std::runtime_error& error) {
        throw UsageError("--size " + options.size + ": " + error.what());
    }
    SceneDrawing drawing(description, live.instance(), static_cast<float>(width) / static_cast<float>(height));
    const std::filesystem::path directory = prepareOutputDirectory(options.outDirectory);

    // Frame 0 is the initial state; each step advances one frame of the scene's dt. The PNGs
    // stay temporary until the last one is written: an interrupted, failed or non-finite render
    // leaves none behind.
    OutputTransaction outputs(source.builtin ? std::vector<std::string>{}
                                             : std::vector<std::string>{options.scene});
    const InterruptGuard interruptGuard;
    std::size_t next = 0;
    for (long long frame = 0; next < frames.size(); ++frame) {
        if (const int signal = interruptSignal(); signal != 0) {
            std::fprintf(stderr, "substep render: interrupted after %zu of %zu images; none written\n", next,
                         frames.size());
            return 128 + signal;
        }
        if (frame > 0) live.step();
        warnAboutDroppedContacts("render", live.world(), frame);
        if (!live.world().isFinite()) {
            std::fprintf(stderr,
                         "substep render: the state turned non-finite at frame %lld, after %zu of %zu "
                         "images; none written\n",
                         frame, next, frames.size());
            return 1;
        }
        if (frames[next] != frame) continue;
        render::RenderScene picture = drawing.draw(live.instance());
        // A script may ask for a camera of its own (one following a body).
        if (live.script() != nullptr)
            if (const std::optional<SceneCamera> camera = live.script()->camera(live.instance()))
                picture.camera = renderCamera(*camera);
        renderer.render(picture, target->target());
        AtomicFile& file = outputs.add("--out", (directory / frameFileName(frame)).string());
        file.write(render::encodePng(target->readPixels()));
        ++next;
    }
    outputs.commit();

    std::printf("rendered %zu image%s of %s (%dx%d, %s) to %s\n", frames.size(), frames.size() == 1 ? "" : "s",
                source.label.c_str(), width, height, context->backendName().c_str(), directory.c_str());
    return 0;
}

}  // namespace

std::pair<int, int> parseImageSize(const std::string& text) {
    const std::size_t cross = text.find('x');
    if (cross == std::string::npos) {
        throw UsageError("--size: expected WIDTHxHEIGHT such as 1280x720, got '" + text + "'");
    }
    const std::string_view view(text);
    const int width = static_cast<int>(parseInteger("--size (width)", view.substr(0, cross), 1, kMaxImageSide));
    const int height = static_cast<int>(parseInteger("--size (height)", view.substr(cross + 1), 1, kMaxImageSide));
    if (static_cast<long long>(width) * height > kMaxImagePixels) {
        throw UsageError("--size " + text + ": at most " + std::to_string(kMaxImagePixels) + " pixels");
    }
    return {width, height};
}

std::vector<long long> parseFrameList(const std::string& text) {
    std::set<long long> frames;
    for (const std::string_view item : split(text, ',')) {
        const std::vector<std::string_view> stepParts = split(item, ':');
        const std::vector<std::string_view> bounds = split(stepParts[0], '-');
        if (stepParts.size() > 2 || bounds.size() > 2 || (stepParts.size() == 2 && bounds.size() == 1)) {
            throw UsageError("--frames: '" + std::string(item) + "' is not a frame, a range A-B or A-B:STEP");
        }
        const long long first = parseInteger("--frames", bounds[0], 0, kMaxRenderFrame);
        const long long last = bounds.size() == 2 ? parseInteger("--frames", bounds[1], 0, kMaxRenderFrame) : first;
        const long long step = stepParts.size() == 2 ? parseInteger("--frames (step)", stepParts[1], 1, kMaxRenderFrame) : 1;
        if (last < first) {
            throw UsageError("--frames: the range '" + std::string(item) + "' ends before it starts");
        }
        for (long long frame = first; frame <= last; frame += step) {
            frames.insert(frame);
            if (frames.size() > kMaxRenderImages) {
                throw UsageError("--frames: more than " + std::to_string(kMaxRenderImages) + " images");
            }
        }
    }
    return {frames.begin(), frames.end()};
}

std::string frameFileName(long long frame) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%05lld.png", frame);
    return name;
}

CLI::App* addRenderCommand(CLI::App& app, RenderOptions& options) {
    CLI::App* command = app.add_subcommand("render", "Headless PNGs of a scene (EGL; OSMesa where EGL is missing)");
    command->add_option("SCENE", options.scene, "A built-in scene name or a .json scene file")->required();
    command->add_option("--frames", options.frames, "Frames to draw: 0,40,120 or ranges 0-120 and 0-120:40")
        ->type_name("LIST")
        ->required();
    command->add_option("--out", options.outDirectory, "Folder for frame_NNNNN.png (created if missing)")
        ->type_name("DIR")
        ->required();
    command->add_option("--size", options.size, "Image size in pixels (default 1280x720)")->type_name("WxH");
    command->add_option("--set", options.knobs, "Turn a scene knob, e.g. --set velocity_pass=0 (repeatable)")
        ->type_name("NAME=VALUE");
    return command;
}

int renderCommand(const RenderOptions& options) {
    return runReportingErrors("render", [&] { return renderFrames(options); });
}

}  // namespace substep
