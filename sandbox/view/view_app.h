#pragma once
/// The interactive viewer's frame loop: a GLFW window with Dear ImGui, the runs (one, or two in
/// compare mode: compare_session.h) stepped and drawn by the renderer into the view beside the
/// docked panel (view_layout.h) every frame. Keys and clicks arrive through a queue
/// (input_queue.h), so no tap is lost at any frame rate; where the panel does not take the
/// mouse, a left drag orbits the camera the runs share and Ctrl + left drag grabs a body
/// (body_dragger.h) in the run under the cursor. Paused and untouched, the window sleeps.

#include "scene_source.h"
#include "view/compare_session.h"

#include "render/image.h"
#include "render/render_quality.h"

#include <optional>
#include <string>

namespace substep::view {

struct ViewAppOptions {
    int width = 1280;   ///< window size in screen pixels
    int height = 720;
    /// Run this many frames, one scene dt each with no waiting for real time, then stop; 0 runs
    /// until the window is closed.
    long long frames = 0;
    bool captureLastFrame = false;  ///< keep the last frame's pixels (scripted runs)
    /// Start in compare mode with these (left, right) solver settings.
    std::optional<CompareSplits> compare;
    /// The rendering quality; unset: chosen from the GL renderer (render_quality.h).
    std::optional<render::QualityLevel> quality;
    bool hidePanel = false;  ///< start with the UI hidden, as Tab does
};

/// How long a scripted run's frames took (ms, medians over the frames after the first ten).
struct ViewFrameTiming {
    long long frames = 0;   ///< frames timed
    double frameMs = 0.0;   ///< the whole frame, the buffer swap included
    double physicsMs = 0.0;
    double renderMs = 0.0;  ///< draw calls (CPU side)
    double swapMs = 0.0;
    /// CPU time of the whole process, every thread (a software rasteriser's too), from the start
    /// of the drawing to the end of the swap: what drawing costs whatever else loads the machine.
    double renderCpuMs = 0.0;
    std::string glRenderer;              ///< GL_RENDERER of the window's context
    render::QualityLevel quality = render::QualityLevel::Full;
};

struct ViewAppResult {
    bool finite = true;                     ///< the state never turned non-finite
    std::optional<render::Image> lastFrame;  ///< the window's last frame, top row first
    ViewFrameTiming timing;                 ///< scripted runs
};

/// Opens the window on `source` and runs the loop. Throws render::ContextError when no window
/// can be made, std::runtime_error on a GL failure.
ViewAppResult runViewApp(SceneSource source, const ViewAppOptions& options);

}  // namespace substep::view
