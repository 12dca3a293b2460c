#include "view/view_app.h"

#include "view/compare_session.h"
#include "view/debug_layer_panel.h"
#include "view/frame_stats.h"
#include "view/glfw_context.h"
#include "view/input_queue.h"
#include "view/key_driver.h"
#include "view/orbit_camera.h"
#include "view/scene_file_watch.h"
#include "view/screenshot.h"
#include "view/view_controls.h"
#include "view/view_layout.h"
#include "view/view_panel.h"

#include "render/offscreen_target.h"
#include "render/renderer.h"

#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <filesystem>
#include <memory>
#include <stdexcept>

namespace substep::view {

namespace {

using Clock = std::chrono::steady_clock;

double millisecondsSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

/// CPU time the process has used so far, all its threads (ms).
double processCpuMs() {
    timespec now{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
    return 1e3 * static_cast<double>(now.tv_sec) + 1e-6 * static_cast<double>(now.tv_nsec);
}

/// Dear ImGui's context and its two backends, torn down in reverse order even when the loop
/// throws.
class ImGuiLayer {
  public:
    explicit ImGuiLayer(GLFWwindow* window) {
        IMGUI_CHECKVERSION();
        ImGui::CreateContext();
        // No imgui.ini: the panel's place is set in code, and a viewer run from a test's folder
        // should leave nothing behind.
        ImGui::GetIO().IniFilename = nullptr;
        ImGui::StyleColorsDark();
        ImGui::GetStyle().Alpha = 0.94f;
        // Chains to the callbacks already installed (the input queue's).
        ImGui_ImplGlfw_InitForOpenGL(window, true);
        if (!ImGui_ImplOpenGL3_Init("#version 330 core")) {
            ImGui_ImplGlfw_Shutdown();
            ImGui::DestroyContext();
            throw std::runtime_error("Dear ImGui's OpenGL 3 backend could not start");
        }
    }
    ~ImGuiLayer() {
        ImGui_ImplOpenGL3_Shutdown();
        ImGui_ImplGlfw_Shutdown();
        ImGui::DestroyContext();
    }
    ImGuiLayer(const ImGuiLayer&) = delete;
    ImGuiLayer& operator=(const ImGuiLayer&) = delete;

    void newFrame() {
        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        ImGui::NewFrame();
    }
    void render() {
        ImGui::Render();
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    }
};

/// What the left button is doing since its press in the view, and where it was pressed.
enum class LeftDrag { None, Orbit, Grab, Missed };
struct LeftButton {
    LeftDrag drag = LeftDrag::None;
    float pressX = 0.0f;
    float pressY = 0.0f;
};

/// A press and release closer than this (screen units) is a click: it selects.
constexpr float kClickSlop = 4.0f;

/// The mouse in the view: the frame's queued clicks first, at the positions they happened (a
/// Ctrl-click shorter than a frame still grabs), then the drags by the cursor's motion. A left
/// press without Ctrl orbits, and released where it was pressed selects the body there for the
/// inspector; with Ctrl it grabs the body under the cursor, and a near miss does nothing until
/// the button is released.
void steerMouse(OrbitCamera& camera, CompareSession& session, const ViewArea& area,
                std::span<const InputEvent> events, LeftButton& left) {
    const ImGuiIO& io = ImGui::GetIO();
    // The ray through window point (x, y) in the view of run `index`.
    const auto ray = [&](std::size_t index, float x, float y) {
        const CompareSession::Part part = session.part(index, area);
        return cursorRay(camera.camera(), x - part.left, y - area.top, part.width, area.height);
    };
    const auto inView = [&](float x, float y) {
        return x >= area.left && x < area.left + area.width && y >= area.top && y < area.top + area.height;
    };
    for (const InputEvent& event : events) {
        if (event.kind != InputEvent::Kind::MouseButton || event.code != GLFW_MOUSE_BUTTON_LEFT) continue;
        const auto x = static_cast<float>(event.x);
        const auto y = static_cast<float>(event.y);
        if (event.action == GLFW_PRESS) {
            if (io.WantCaptureMouse || !inView(x, y)) continue;
            left.pressX = x;
            left.pressY = y;
            if (!grabsBody(event.mods)) {
                left.drag = LeftDrag::Orbit;
                continue;
            }
            const std::size_t under = session.runAt(x, area);
            left.drag = session.run(under).grab(ray(under, x, y)) ? LeftDrag::Grab : LeftDrag::Missed;
        } else if (event.action == GLFW_RELEASE) {
            if (const std::optional<std::size_t> held = session.dragging()) session.run(*held).release();
            if (left.drag == LeftDrag::Orbit && std::abs(x - left.pressX) < kClickSlop &&
                std::abs(y - left.pressY) < kClickSlop) {
                const std::size_t under = session.runAt(x, area);
                // Near a joint's anchor (12 pixels) the click selects the joint.
                session.run(under).select(ray(under, x, y), camera.camera().fovY / std::max(area.height, 1.0f));
            }
            left.drag = LeftDrag::None;
        }
    }
    if (const std::optional<std::size_t> held = session.dragging()) {
        session.run(*held).drag(ray(*held, io.MousePos.x, io.MousePos.y));
    }
    if (left.drag == LeftDrag::Orbit) camera.orbit(io.MouseDelta.x, io.MouseDelta.y);
    if (io.WantCaptureMouse || !inView(io.MousePos.x, io.MousePos.y)) return;
    if (io.MouseDown[ImGuiMouseButton_Right] || io.MouseDown[ImGuiMouseButton_Middle]) {
        camera.pan(io.MouseDelta.x, io.MouseDelta.y, area.height);
    }
    if (io.MouseWheel != 0.0f) camera.zoom(io.MouseWheel);
}

/// The F1 overlay: every control, centred over the view.
void drawHelpOverlay(const ViewArea& area) {
    ImGui::SetNextWindowPos(ImVec2(area.left + area.width / 2.0f, area.top + area.height / 2.0f), ImGuiCond_Always,
                            ImVec2(0.5f, 0.5f));
    ImGui::SetNextWindowBgAlpha(0.92f);
    ImGui::SetNextWindowSizeConstraints(ImVec2(0.0f, 0.0f), ImVec2(area.width - 20.0f, area.height - 20.0f));
    ImGui::Begin("controls (F1 closes)", nullptr,
                 ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoSavedSettings |
                     ImGuiWindowFlags_NoCollapse);
    if (ImGui::BeginTable("controls", 2, ImGuiTableFlags_RowBg)) {
        for (const ControlHelp& control : viewControls()) {
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(control.keys);
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(control.does);
        }
        ImGui::EndTable();
    }
    ImGui::End();
}

/// The window's title: the scene, and while paused the frame it is paused at (what a window
/// list shows, and what the tests read with xdotool).
std::string windowTitle(CompareSession& session) {
    std::string title = "Substep - " + session.source().label;
    if (!session.playback().playing) {
        char paused[128];
        const ViewSession& first = session.first();
        if (first.frameOpen()) {
            // Mid-frame (substep stepping): the frames done and the substeps of the next one.
            std::snprintf(paused, sizeof paused, " (paused at frame %lld, substep %d/%d, t = %.3f s)", first.frame(),
                          first.frameSubstepsDone(), first.frameSubsteps(), first.simulatedTime());
        } else {
            std::snprintf(paused, sizeof paused, " (paused at frame %lld, t = %.3f s)", first.frame(),
                          first.simulatedTime());
        }
        title += paused;
    }
    return title;
}

double median(std::vector<double> values) {
    if (values.empty()) return 0.0;
    const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
    std::nth_element(values.begin(), middle, values.end());
    return *middle;
}

/// The scripted run's timing: medians of the frames after the first ten (shader compiles,
/// first uploads).
void summariseTiming(const std::vector<FrameSample>& samples, ViewFrameTiming& timing) {
    const std::size_t skip = std::min<std::size_t>(10, samples.size() / 2);
    std::vector<double> frame;
    std::vector<double> physics;
    std::vector<double> render;
    std::vector<double> swap;
    for (std::size_t i = skip; i < samples.size(); ++i) {
        frame.push_back(samples[i].frameMs);
        physics.push_back(samples[i].physicsMs);
        render.push_back(samples[i].renderMs);
        swap.push_back(samples[i].swapMs);
    }
    timing.frames = static_cast<long long>(frame.size());
    timing.frameMs = median(frame);
    timing.physicsMs = median(physics);
    timing.renderMs = median(render);
    timing.swapMs = median(swap);
}

}  // namespace

ViewAppResult runViewApp(SceneSource source, const ViewAppOptions& options) {
    GlfwContext context("Substep - " + source.label, {options.width, options.height});
    const bool scripted = options.frames > 0;
    context.setVsync(!scripted);
    const render::GlApi gl = context.loadApi();
    const auto* rendererName = reinterpret_cast<const char*>(gl.GetString(GL_RENDERER));
    ViewStatus status;
    status.glRenderer = rendererName != nullptr ? rendererName : "";
    status.quality = options.quality.value_or(render::qualityForRenderer(status.glRenderer));
    render::Renderer renderer(gl, render::rendererSettings(render::qualitySettings(status.quality)));
    InputQueue input(context.window());  // before ImGui, whose callbacks chain to it
    ImGuiLayer imgui(context.window());
    bool panelShown = !options.hidePanel;
    bool helpShown = false;

    const ViewArea startArea = viewArea(static_cast<float>(options.width), static_cast<float>(options.height), panelShown);
    CompareSession session(std::move(source), startArea.width / startArea.height);
    if (options.compare) session.compare(options.compare);
    OrbitCamera camera(session.startCamera());
    ViewPanel panel;
    KeyDriver keyDriver;  // the scene's key-bound knobs (the RC car's throttle and steering)
    std::string loadError;
    FrameStats stats;
    std::vector<FrameSample> scriptedSamples;
    std::vector<double> scriptedRenderCpu;  ///< the drawing's CPU time of each scripted frame (ms)
    ViewAppResult result;
    status.stats = &stats;
    // The scene is drawn multisampled here and resolved into the window, so the quality level
    // can change the samples without a new window.
    std::unique_ptr<render::OffscreenTarget> multisampled;
    int multisampledSamples = 0;  ///< as asked for (the target holds what the driver gave)
    LeftButton left;
    std::string title;

    SceneFileWatch fileWatch;
    fileWatch.watch(session.source().builtin ? "" : session.source().label);
    std::uint64_t seenEvents = input.eventCount();
    int redrawFrames = 2;  // ImGui settles its layout over a frame or two
    Clock::time_point lastFrameStart = Clock::now();
    for (long long frame = 0; !context.shouldClose(); ++frame) {
        // Paused, untouched and not dragging: sleep until an event (or the file watch's next look)
        // instead of drawing the same picture again.
        const bool idle = !scripted && !session.playback().playing && !session.dragging() && redrawFrames == 0;
        if (idle) {
            glfwWaitEventsTimeout(std::chrono::duration<double>(SceneFileWatch::interval).count());
        } else {
            glfwPollEvents();
        }
        const bool fileChanged = fileWatch.changed();
        if (input.eventCount() != seenEvents) {
            seenEvents = input.eventCount();
            redrawFrames = 3;
        }
        if (idle && redrawFrames == 0 && !fileChanged) {
            --frame;
            continue;
        }
        redrawFrames = std::max(redrawFrames - 1, 0);
        const Clock::time_point frameStart = Clock::now();
        const double wallSeconds = std::chrono::duration<double>(frameStart - lastFrameStart).count();
        lastFrameStart = frameStart;
        const std::vector<InputEvent>& events = input.take();

        imgui.newFrame();
        const ImGuiIO& io = ImGui::GetIO();
        ViewArea area = viewArea(io.DisplaySize.x, io.DisplaySize.y, panelShown);
        steerMouse(camera, session, area, events, left);

        // Physics: scripted runs step exactly one frame each, so what they show does not depend
        // on speed; otherwise as much as the wall time since the last drawn frame covers.
        const double timeBefore = session.first().simulatedTime();
        const Clock::time_point physicsStart = Clock::now();
        if (scripted) {
            if (session.playback().playing) session.stepOnce();
        } else {
            session.advance(wallSeconds);
        }

        // Keys the scene drives with (the RC car's WASD and arrows) drive it while it plays and
        // are the window's while it is paused (view_controls.h).
        const std::vector<int> drivenKeys = keyDriver.boundKeys(session);
        const KeyActions keys = keyActions(events, io.WantTextInput, session.playback().playing, drivenKeys);
        PanelRequests requests;
        if (keys.toggleUi % 2 != 0) {
            panelShown = !panelShown;
            // This frame already draws the view where Tab put it: a Shift+P queued in the same
            // frame (a slow frame) shoots the view, not the area the panel just left or took.
            area = viewArea(io.DisplaySize.x, io.DisplaySize.y, panelShown);
        }
        if (keys.toggleHelp % 2 != 0) helpShown = !helpShown;
        if (panelShown) requests = panel.draw(session, status, area, loadError);
        if (helpShown) drawHelpOverlay(area);
        if (keys.togglePlay % 2 != 0) session.playback().playing = !session.playback().playing;
        requests.restart |= keys.restart;
        for (int step = 0; step < keys.steps; ++step) session.stepOnce();
        if (keys.scrub != 0) session.scrubBy(keys.scrub);
        for (int substep = 0; substep < keys.substeps; ++substep) session.stepSubstep();
        keyDriver.update(session);
        if (toggleLayersByKey(keys, session.first().controls().drawing)) session.applyDrawingOptions();
        if (keys.resetCamera || keys.restart) camera = OrbitCamera(session.startCamera());

        if (requests.loadScene) {
            try {
                session.load(resolveScene(*requests.loadScene));
                camera = OrbitCamera(session.startCamera());
                loadError.clear();
            } catch (const std::exception& error) {
                loadError = error.what();
            }
            fileWatch.watch(session.source().builtin ? "" : session.source().label);
        } else if (fileChanged) {
            // The scene's file was saved: reload it, keeping the camera where the user put it.
            try {
                session.load(resolveScene(session.source().label));
                loadError.clear();
            } catch (const std::exception& error) {
                loadError = error.what();  // a half-edited file: keep the last good scene
            }
        }
        // Compare mode starts both runs afresh; the camera stays where the user put it.
        if (requests.compare) session.compare(*requests.compare ? std::optional(session.splits()) : std::nullopt);
        if (requests.restart) session.restart();
        if (requests.controlsChanged) session.applyControls();
        if (requests.drawingChanged) session.applyDrawingOptions();
        if (requests.step) session.stepOnce();
        if (requests.substep) session.stepSubstep();
        if (requests.scrubTo) session.scrubTo(*requests.scrubTo);
        if (requests.scrubBy != 0) session.scrubBy(requests.scrubBy);
        if (requests.resetCamera) camera = OrbitCamera(session.startCamera());
        if (requests.quality) {
            status.quality = *requests.quality;
            renderer.setSettings(render::rendererSettings(render::qualitySettings(status.quality)));
        }
        if (requests.loadScene || requests.restart || requests.compare) stats.clear();
        const double physicsMs = millisecondsSince(physicsStart);
        const double simulated = std::max(session.first().simulatedTime() - timeBefore, 0.0);

        if (const std::string now = windowTitle(session); now != title) {
            title = now;
            glfwSetWindowTitle(context.window(), title.c_str());
        }

        const render::PixelSize size = context.framebufferSize();
        double renderMs = 0.0;
        const double renderCpuStart = processCpuMs();
        if (size.width > 0 && size.height > 0) {  // minimised: nothing to draw into
            const Clock::time_point renderStart = Clock::now();
            const render::RenderTarget view = pixelArea(area, size, io.DisplaySize.x, io.DisplaySize.y);
            // The panel's side: cleared, since the scene is drawn beside it only.
            gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
            gl.Viewport(0, 0, size.width, size.height);
            gl.ClearColor(0.08f, 0.08f, 0.09f, 1.0f);
            gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
            // The scene goes through an offscreen buffer when it is multisampled or drawn at a
            // lower resolution (a multisampled resolve cannot scale, so those two exclude each
            // other), and is resolved into the view's pixels; else straight into the window.
            const render::RenderQuality quality = render::qualitySettings(status.quality);
            const int samples = quality.msaaSamples;
            const float scale = samples > 0 ? 1.0f : std::clamp(quality.renderScale, 0.1f, 1.0f);
            const render::PixelSize bufferSize{std::max(static_cast<int>(std::ceil(size.width * scale)), 1),
                                               std::max(static_cast<int>(std::ceil(size.height * scale)), 1)};
            const bool offscreen = samples > 0 || scale < 1.0f;
            if (!offscreen) {
                multisampled.reset();
            } else if (!multisampled || multisampled->target().size.width != bufferSize.width ||
                       multisampled->target().size.height != bufferSize.height || multisampledSamples != samples) {
                multisampled = std::make_unique<render::OffscreenTarget>(gl, bufferSize, samples);
                multisampledSamples = samples;
            }
            render::RenderTarget drawn = view;
            if (multisampled) {
                drawn = pixelArea(area, bufferSize, io.DisplaySize.x, io.DisplaySize.y);
                drawn.framebuffer = multisampled->target().framebuffer;
            }
            for (std::size_t index = 0; index < session.runCount(); ++index) {
                renderer.render(session.run(index).draw(camera.camera()), session.target(index, drawn));
            }
            if (multisampled) multisampled->resolveInto(0, drawn, view);

            status.triangles = renderer.lastTriangleCount();
            if (keys.screenshotViewOnly) {
                const std::filesystem::path path =
                    screenshotPath(std::filesystem::current_path(), session.source().label, session.first().frame());
                try {
                    saveScreenshot(readBackBuffer(gl, view), path);
                    status.notice = "saved " + path.filename().string() + " (the view)";
                } catch (const std::exception& error) {
                    status.notice = error.what();
                }
            }
            imgui.render();
            const render::RenderTarget whole{.framebuffer = 0, .size = size};
            if (keys.screenshot) {
                const std::filesystem::path path =
                    screenshotPath(std::filesystem::current_path(), session.source().label, session.first().frame());
                try {
                    saveScreenshot(readBackBuffer(gl, whole), path);
                    status.notice = "saved " + path.filename().string();
                } catch (const std::exception& error) {
                    status.notice = error.what();
                }
            }
            if (scripted && options.captureLastFrame && frame + 1 == options.frames) {
                result.lastFrame = readBackBuffer(gl, whole);
            }
            renderMs = millisecondsSince(renderStart);
        } else {
            ImGui::Render();
        }
        const Clock::time_point swapStart = Clock::now();
        context.swapBuffers();
        const FrameSample sample{.frameMs = millisecondsSince(frameStart),
                                 .physicsMs = physicsMs,
                                 .renderMs = renderMs,
                                 .swapMs = millisecondsSince(swapStart),
                                 .simulatedSeconds = simulated,
                                 .playing = session.playback().playing};
        stats.record(sample);
        if (scripted) {
            scriptedSamples.push_back(sample);
            scriptedRenderCpu.push_back(processCpuMs() - renderCpuStart);
        }
        if (scripted && frame + 1 >= options.frames) break;
    }
    for (std::size_t index = 0; index < session.runCount(); ++index) {
        result.finite = result.finite && session.run(index).finite();
    }
    summariseTiming(scriptedSamples, result.timing);
    const std::size_t skip = std::min<std::size_t>(10, scriptedRenderCpu.size() / 2);  // as summariseTiming
    result.timing.renderCpuMs =
        median(std::vector<double>(scriptedRenderCpu.begin() + static_cast<std::ptrdiff_t>(skip), scriptedRenderCpu.end()));
    result.timing.glRenderer = status.glRenderer;
    result.timing.quality = status.quality;
    return result;
}

}  // namespace substep::view
