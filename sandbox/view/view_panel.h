#pragma once
/// The viewer's ImGui panel: scene picker and file box, play/pause/step/restart, time scale, the
/// compare mode switch, substeps and iterations per run, gravity, the debug layers, and per run
/// live plots of total energy, of the largest joint error and of a chain's elongation, with its
/// physics time. It edits the controls in place and returns what must happen to the session as a
/// whole (a new scene, a restart, compare mode), which the app then does. In compare mode each
/// run's measures are drawn over its own half of the window.

#include "view/compare_session.h"

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
    std::optional<bool> compare;   ///< compare mode switched on or off
};

class ViewPanel {
  public:
    /// Draws the panel for this ImGui frame. `loadError` is shown under the file box when set.
    PanelRequests draw(CompareSession& session, const FrameTimes& times, const std::string& loadError);

  private:
    char path_[512] = {};  ///< the file box's text
    std::optional<bool> shownComparing_;  ///< compare mode at the last frame: the panel refits when it changes
};

}  // namespace substep::view
