#include "view/column_plots.h"

#include "state_columns.h"

#include <algorithm>

namespace substep::view {

void ColumnPlots::reset(const SceneInstance& scene) {
    columns_ = stateColumnNames(scene);
    columns_.erase(columns_.begin());  // `frame`: the plots' own axis
    std::vector<Plot> kept;
    for (Plot& plot : plots_) {
        const auto found = std::find(columns_.begin(), columns_.end(), plot.column);
        if (found == columns_.end()) continue;
        plot.value = static_cast<std::size_t>(found - columns_.begin());
        plot.history.clear();
        kept.push_back(std::move(plot));
    }
    plots_ = std::move(kept);
    newestFrame_ = shownFrame_ = -1;
}

void ColumnPlots::record(const SceneInstance& scene, long long frame, double t) {
    if (newestFrame_ >= 0 && frame <= newestFrame_) {
        const auto later = static_cast<std::size_t>(newestFrame_ - frame + 1);
        for (Plot& plot : plots_) plot.history.dropNewest(later);
    }
    newestFrame_ = shownFrame_ = frame;
    if (plots_.empty()) return;
    // sampleState's row starts at `t`, as columns_ does.
    sampleState(scene, t, row_);
    for (Plot& plot : plots_) plot.history.push(static_cast<float>(row_[plot.value]));
}

void ColumnPlots::showUpTo(long long frame) { shownFrame_ = std::min(frame, newestFrame_); }

bool ColumnPlots::add(std::string_view column) {
    const auto found = std::find(columns_.begin(), columns_.end(), column);
    if (found == columns_.end()) return false;
    if (std::any_of(plots_.begin(), plots_.end(), [&](const Plot& plot) { return plot.column == column; })) return false;
    plots_.push_back({.column = *found, .value = static_cast<std::size_t>(found - columns_.begin())});
    return true;
}

void ColumnPlots::remove(std::size_t index) {
    if (index < plots_.size()) plots_.erase(plots_.begin() + static_cast<std::ptrdiff_t>(index));
}

std::size_t ColumnPlots::shownCount(const Plot& plot) const {
    const std::size_t count = plot.history.count();
    const auto hidden = static_cast<std::size_t>(std::max(newestFrame_ - shownFrame_, 0LL));
    return count > hidden ? count - hidden : 0;
}

}  // namespace substep::view
