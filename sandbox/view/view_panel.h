#pragma once
/// The viewer's ImGui panel, docked at the window's left edge: scene picker and file box,
/// play/pause/step/restart, time scale, rendering quality, the
/// compare mode switch, substeps and iterations per run, gravity, the debug layers, and per run
/// live plots of total energy, of the largest joint error and of a chain's elongation, with its
/// physics time, and plots of any CSV column the user picks (column_plot_panel.h). It edits the controls in place and returns what must happen to the session as a
/// whole (a new scene, a restart, compare mode), which the app then does. In compare mode each
/// run's measures are drawn over its own half of the window.

#include "view/compare_session.h"
#include "view/column_plot_panel.h"
#include "view/frame_stats.h"
#include "view/view_layout.h"

#include "render/render_quality.h"

#include <optional>
#include <string>

namespace substep::view {

/// What the window reports in the panel beside the session's own state.
struct ViewStatus {
    const FrameStats* stats = nullptr;  ///< frame times and the real-time factor
    render::QualityLevel quality = render::QualityLevel::Full;
    std::string glRenderer;   ///< GL_RENDERER, which chose the starting quality
    long long triangles = 0;  ///< drawn in the view pass of the last frame
    std::string notice;       ///< the last screenshot saved (or why it failed)
};

/// What the user asked for in this frame beyond editing controls().
struct PanelRequests {
    std::optional<std::string> loadScene;  ///< a built-in name or a .json path
    bool restart = false;
    bool step = false;
    bool substep = false;  ///< one substep, its corrections drawn
    bool controlsChanged = false;  ///< substeps, iterations or gravity
    bool drawingChanged = false;   ///< a debug layer toggled
    std::optional<bool> compare;   ///< compare mode switched on or off
    bool resetCamera = false;
    std::optional<render::QualityLevel> quality;  ///< a rendering quality chosen
    std::optional<long long> scrubTo;  ///< a frame of the timeline chosen on its slider
    long long scrubBy = 0;              ///< frames back (< 0) or forward through the timeline
};

class ViewPanel {
  public:
    /// Draws the panel for this ImGui frame, docked at the left of the window beside `view`
    /// (view_layout.h), and in compare mode each run's measures over its part of the view.
    /// `loadError` is shown, wrapped, under the file box when set.
    PanelRequests draw(CompareSession& session, const ViewStatus& status, const ViewArea& view,
                       const std::string& loadError);

  private:
    char path_[512] = {};  ///< the file box's text
    ColumnPlotPanel columnPlotPanel_;  ///< the picker of CSV columns to plot
};

}  // namespace substep::view
