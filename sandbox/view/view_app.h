#pragma once
/// The interactive viewer's frame loop: a GLFW window with Dear ImGui, the runs (one, or two in
/// compare mode: compare_session.h) stepped and drawn by the renderer into their parts of the
/// window's default framebuffer every frame; where the panel does not take the mouse, it drags
/// bodies (body_dragger.h) in the run under the cursor and steers the orbit camera they share.

#include "scene_source.h"
#include "view/compare_session.h"

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
    /// Start in compare mode with these (left, right) solver settings.
    std::optional<CompareSplits> compare;
};

struct ViewAppResult {
    bool finite = true;                     ///< the state never turned non-finite
    std::optional<render::Image> lastFrame;  ///< the window's last frame, top row first
};

/// Opens the window on `source` and runs the loop. Throws render::ContextError when no window
/// can be made, std::runtime_error on a GL failure.
ViewAppResult runViewApp(SceneSource source, const ViewAppOptions& options);

}  // namespace substep::view
