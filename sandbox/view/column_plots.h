#pragma once
/// Plots of any column `substep run --csv` would write for the scene (state_columns.h): the
/// bodies' poses and velocities, the joints' forces and errors, the energies, the soft bodies'
/// readouts. The values are sampled by the code that writes the CSV, so a plotted value is the
/// CSV's at the same frame (rounded to float). The plots follow the timeline: scrubbed back they
/// end at the shown frame, and a step from there drops the later samples as the timeline drops
/// its later states. Knows nothing of ImGui (column_plot_panel.h draws them).

#include "view/plot_history.h"

#include "scene/scene.h"

#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace substep::view {

class ColumnPlots {
  public:
    /// Samples kept per plot (10 s at 60 frames per second, as the timeline).
    static constexpr std::size_t kCapacity = 600;

    /// One plotted column and its latest samples.
    struct Plot {
        std::string column;
        std::size_t value = 0;  ///< its position in sampleState's row
        PlotHistory history{kCapacity};
    };

    /// Takes `scene`'s columns and forgets every sample. Plots of columns the scene also has
    /// stay (a restart or a reload keeps them); the others go.
    void reset(const SceneInstance& scene);
    /// Samples the plotted columns for the state after `frame` at time t, as `run --csv` writes
    /// that frame's row. A frame at or before the newest sampled one (a step from a scrubbed-back
    /// frame) first drops the samples from it on.
    void record(const SceneInstance& scene, long long frame, double t);
    /// The timeline shows `frame`: the plots end there until the next record.
    void showUpTo(long long frame);

    /// Every column that can be plotted, in the CSV's order (`t`, the energies, ... ; not `frame`).
    std::span<const std::string> columns() const { return columns_; }
    /// Adds a plot of `column` (sampled from the next record on); false when the scene has no such
    /// column or it is plotted already.
    bool add(std::string_view column);
    /// Removes plot `index` (as plots() orders them); nothing when out of range.
    void remove(std::size_t index);
    std::span<const Plot> plots() const { return plots_; }

    /// How many of `plot`'s samples are shown: all but those after the shown frame.
    std::size_t shownCount(const Plot& plot) const;
    /// Sample `i` of `plot` counted from the oldest.
    static float sampleAt(const Plot& plot, std::size_t i) { return plot.history.at(i); }

  private:
    std::vector<std::string> columns_;
    std::vector<Plot> plots_;
    std::vector<double> row_;     ///< sampleState's row, kept for its storage
    long long newestFrame_ = -1;  ///< the frame of the newest samples, -1 before any
    long long shownFrame_ = -1;   ///< the frame the timeline shows
};

}  // namespace substep::view
