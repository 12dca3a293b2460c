#include "view/view_app.h"

#include "view/glfw_context.h"
#include "view/orbit_camera.h"
#include "view/scene_file_watch.h"
#include "view/view_panel.h"
#include "view/compare_session.h"
#include "view/key_driver.h"

#include "render/renderer.h"

#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include <chrono>
#include <cstring>
#include <stdexcept>

namespace substep::view {

namespace {

using Clock = std::chrono::steady_clock;

double millisecondsSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
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

/// The mouse, where the panel does not want it: a left press on a body grabs it in the run under
/// the cursor and drags it until released; elsewhere a left drag orbits the camera.
void steerMouse(OrbitCamera& camera, CompareSession& session) {
    const ImGuiIO& io = ImGui::GetIO();
    // The ray through the cursor in the view of run `index`, which fills its part of the window.
    const auto ray = [&](std::size_t index) {
        const CompareSession::Part part = session.part(index, io.DisplaySize.x);
        return cursorRay(camera.camera(), io.MousePos.x - part.left, io.MousePos.y, part.width, io.DisplaySize.y);
    };
    if (const std::optional<std::size_t> held = session.dragging()) {
        if (io.MouseDown[ImGuiMouseButton_Left]) {
            session.run(*held).drag(ray(*held));
        } else {
            session.run(*held).release();
        }
        return;
    }
    if (io.WantCaptureMouse) return;
    const std::size_t under = session.runAt(io.MousePos.x, io.DisplaySize.x);
    if (ImGui::IsMouseClicked(ImGuiMouseButton_Left) && session.run(under).grab(ray(under))) return;
    if (io.MouseDown[ImGuiMouseButton_Left]) {
        camera.orbit(io.MouseDelta.x, io.MouseDelta.y);
    } else if (io.MouseDown[ImGuiMouseButton_Right] || io.MouseDown[ImGuiMouseButton_Middle]) {
        camera.pan(io.MouseDelta.x, io.MouseDelta.y, io.DisplaySize.y);
    }
    if (io.MouseWheel != 0.0f) camera.zoom(io.MouseWheel);
}

/// Space, S and R do what the panel's play, step and restart buttons do, unless a text box
/// has the keyboard (S not while the scene drives a knob with it).
void readShortcuts(Playback& playback, PanelRequests& requests, bool stepKey) {
    if (ImGui::GetIO().WantCaptureKeyboard) return;
    if (ImGui::IsKeyPressed(GLFW_KEY_SPACE, false)) playback.playing = !playback.playing;
    if (stepKey && ImGui::IsKeyPressed(GLFW_KEY_S)) requests.step = true;
    if (ImGui::IsKeyPressed(GLFW_KEY_R, false)) requests.restart = true;
}

/// The back buffer as drawn, top row first. Alpha is set opaque: what the blending of the
/// panel leaves there is not part of the picture.
render::Image readBackBuffer(const render::GlApi& gl, render::PixelSize size) {
    render::Image image{size.width, size.height, std::vector<uint8_t>(static_cast<std::size_t>(size.width) * size.height * 4)};
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl.ReadBuffer(GL_BACK);
    gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
    std::vector<uint8_t> bottomUp(image.rgba.size());
    gl.ReadPixels(0, 0, size.width, size.height, GL_RGBA, GL_UNSIGNED_BYTE, bottomUp.data());
    if (const GLenum error = gl.GetError(); error != GL_NO_ERROR) {
        throw std::runtime_error("reading the window's pixels failed: " + render::glErrorName(error));
    }
    const std::size_t row = static_cast<std::size_t>(size.width) * 4;
    for (int y = 0; y < size.height; ++y) {
        std::memcpy(&image.rgba[y * row], &bottomUp[(size.height - 1 - y) * row], row);
    }
    for (std::size_t i = 3; i < image.rgba.size(); i += 4) image.rgba[i] = 255;
    return image;
}

}  // namespace

ViewAppResult runViewApp(SceneSource source, const ViewAppOptions& options) {
    GlfwContext context("Substep - " + source.label, {options.width, options.height});
    const bool scripted = options.frames > 0;
    context.setVsync(!scripted);
    const render::GlApi gl = context.loadApi();
    render::Renderer renderer(gl);
    ImGuiLayer imgui(context.window());

    const render::PixelSize startSize = context.framebufferSize();
    const float aspect = static_cast<float>(startSize.width) / static_cast<float>(std::max(startSize.height, 1));
    CompareSession session(std::move(source), aspect);
    if (options.compare) session.compare(options.compare);
    OrbitCamera camera(session.startCamera());
    ViewPanel panel;
    KeyDriver keyDriver;  // the scene's key-bound knobs (the RC car's throttle and steering)
    std::string loadError;
    FrameTimes times;
    ViewAppResult result;

    SceneFileWatch fileWatch;
    fileWatch.watch(session.source().builtin ? "" : session.source().label);
    Clock::time_point last = Clock::now();
    for (long long frame = 0; !context.shouldClose(); ++frame) {
        const Clock::time_point frameStart = Clock::now();
        const double wallSeconds = std::chrono::duration<double>(frameStart - last).count();
        last = frameStart;
        glfwPollEvents();
        imgui.newFrame();
        steerMouse(camera, session);

        // Scripted runs step exactly one frame each, so what they show does not depend on speed.
        if (scripted) {
            if (session.playback().playing) session.stepOnce();
        } else {
            session.advance(wallSeconds);
        }

        PanelRequests requests = panel.draw(session, times, loadError);
        readShortcuts(session.playback(), requests, !keyDriver.binds(session, GLFW_KEY_S));
        keyDriver.update(session);
        if (requests.loadScene) {
            try {
                session.load(resolveScene(*requests.loadScene));
                camera = OrbitCamera(session.startCamera());
                loadError.clear();
            } catch (const std::exception& error) {
                loadError = error.what();
            }
            fileWatch.watch(session.source().builtin ? "" : session.source().label);
        } else if (fileWatch.changed()) {
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

        const render::PixelSize size = context.framebufferSize();
        if (size.width > 0 && size.height > 0) {  // minimised: nothing to draw into
            const Clock::time_point renderStart = Clock::now();
            for (std::size_t index = 0; index < session.runCount(); ++index) {
                renderer.render(session.run(index).draw(camera.camera()), session.target(index, size));
            }
            times.renderMs = millisecondsSince(renderStart);
            imgui.render();
            if (scripted && options.captureLastFrame && frame + 1 == options.frames) {
                result.lastFrame = readBackBuffer(gl, size);
            }
        } else {
            ImGui::Render();
        }
        context.swapBuffers();
        times.frameMs = millisecondsSince(frameStart);
        if (scripted && frame + 1 >= options.frames) break;
    }
    for (std::size_t index = 0; index < session.runCount(); ++index) {
        result.finite = result.finite && session.run(index).finite();
    }
    return result;
}

}  // namespace substep::view
