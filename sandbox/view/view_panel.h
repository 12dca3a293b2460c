#pragma once
/// The viewer's ImGui panel: scene picker and file box, play/pause/step/restart, time scale,
/// substeps, iterations, gravity, the debug layers, live plots of total energy and of the largest
/// joint error, and the frame times. It edits the session's controls in place and returns what
/// must happen to the session as a whole (a new scene, a restart), which the app then does.

#include "view/view_session.h"

#include <optional>
#include <string>

namespace substep::view {

/// Times of the last frame, for the readout (ms).
struct FrameTimes {
    double renderMs = 0.0;  ///< the renderer's draw calls, CPU side
    double frameMs = 0.0;   ///< the whole frame, wall clock
};

/// What the user asked for in this frame beyond editing controls().
struct PanelRequests {
    std::optional<std::string> loadScene;  ///< a built-in name or a .json path
    bool restart = false;
    bool step = false;
    bool controlsChanged = false;  ///< substeps, iterations or gravity
    bool drawingChanged = false;   ///< a debug layer toggled
};

class ViewPanel {
  public:
    /// Draws the panel for this ImGui frame. `loadError` is shown under the file box when set.
    PanelRequests draw(ViewSession& session, const FrameTimes& times, const std::string& loadError);

  private:
    char path_[512] = {};  ///< the file box's text
};

}  // namespace substep::view
