#pragma once
/// The panel's plots of CSV columns (column_plots.h): a filter box and a combo of every column
/// the scene's `run --csv` would write, each chosen column a plot with its remove button. In
/// compare mode a column is added to and removed from every run, and each run's plots are drawn
/// with its other measures.

#include "view/compare_session.h"

namespace substep::view {

class ColumnPlotPanel {
  public:
    /// The picker: adds the chosen column to every run.
    void drawPicker(CompareSession& session);

  private:
    char filter_[64] = {};
    std::vector<std::size_t> matches_;  ///< columns matching the filter, kept for their storage
};

/// `run`'s column plots, `height` each, each with a button that removes it from every run of
/// `session`.
void drawColumnPlots(CompareSession& session, ViewSession& run, float height);

}  // namespace substep::view
