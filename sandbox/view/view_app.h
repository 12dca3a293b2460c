#pragma once
/// The interactive viewer's frame loop: a GLFW window with Dear ImGui, the session stepped and
/// drawn by the renderer into the window's default framebuffer every frame; where the panel does
/// not take the mouse, it drags bodies (body_dragger.h) and steers the orbit camera.

#include "scene_source.h"

#include "render/image.h"

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
};

struct ViewAppResult {
    bool finite = true;                     ///< the state never turned non-finite
    std::optional<render::Image> lastFrame;  ///< the window's last frame, top row first
};

/// Opens the window on `source` and runs the loop. Throws render::ContextError when no window
/// can be made, std::runtime_error on a GL failure.
ViewAppResult runViewApp(SceneSource source, const ViewAppOptions& options);

}  // namespace substep::view
