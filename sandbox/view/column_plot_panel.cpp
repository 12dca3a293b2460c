#include "view/column_plot_panel.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

namespace substep::view {

namespace {

/// What PlotLines' getter reads: a plot's shown samples.
struct ShownSamples {
    const ColumnPlots::Plot* plot;
};

float sampleOf(void* data, int index) {
    return ColumnPlots::sampleAt(*static_cast<const ShownSamples*>(data)->plot, static_cast<std::size_t>(index));
}

}  // namespace

void ColumnPlotPanel::drawPicker(CompareSession& session) {
    const ColumnPlots& plots = session.first().columnPlots();
    const std::span<const std::string> columns = plots.columns();
    ImGui::TextUnformatted("plots of CSV columns");
    ImGui::SetNextItemWidth(0.45f * ImGui::GetContentRegionAvail().x);
    ImGui::InputTextWithHint("##column_filter", "filter", filter_, sizeof filter_);
    ImGui::SameLine();
    ImGui::SetNextItemWidth(-1.0f);  // the rest of the row
    if (!ImGui::BeginCombo("##plot", "add a column")) return;
    matches_.clear();
    for (std::size_t i = 0; i < columns.size(); ++i)
        if (filter_[0] == '\0' || columns[i].find(filter_) != std::string::npos) matches_.push_back(i);
    // Thousands of columns in a scene of many named bodies: only the visible rows are made.
    ImGuiListClipper clipper;
    clipper.Begin(static_cast<int>(matches_.size()));
    while (clipper.Step()) {
        for (int row = clipper.DisplayStart; row < clipper.DisplayEnd; ++row) {
            const std::string& column = columns[matches_[static_cast<std::size_t>(row)]];
            if (ImGui::Selectable(column.c_str()))
                for (std::size_t index = 0; index < session.runCount(); ++index) session.run(index).columnPlots().add(column);
        }
    }
    ImGui::EndCombo();
}

void drawColumnPlots(CompareSession& session, ViewSession& run, float height) {
    const ColumnPlots& plots = run.columnPlots();
    std::optional<std::string> removed;
    for (std::size_t index = 0; index < plots.plots().size(); ++index) {
        const ColumnPlots::Plot& plot = plots.plots()[index];
        ImGui::PushID(static_cast<int>(index));
        if (ImGui::SmallButton("x")) removed = plot.column;
        ImGui::SameLine();
        ImGui::TextUnformatted(plot.column.c_str());
        const auto count = static_cast<int>(plots.shownCount(plot));
        float lowest = 0.0f, highest = 0.0f;
        for (int i = 0; i < count; ++i) {
            const float value = ColumnPlots::sampleAt(plot, static_cast<std::size_t>(i));
            lowest = i == 0 ? value : std::min(lowest, value);
            highest = i == 0 ? value : std::max(highest, value);
        }
        // Padded as the other plots are, so a constant column draws as a flat line mid-plot.
        const float magnitude = std::max(std::abs(lowest), std::abs(highest));
        const float pad = std::max({0.05f * (highest - lowest), 1e-4f * magnitude, 1e-9f});
        char overlay[64] = "";
        if (count > 0) std::snprintf(overlay, sizeof overlay, "%.6g", ColumnPlots::sampleAt(plot, static_cast<std::size_t>(count - 1)));
        ShownSamples shown{&plot};
        ImGui::PlotLines("##column", sampleOf, &shown, count, 0, overlay, lowest - pad, highest + pad,
                         ImVec2(ImGui::GetContentRegionAvail().x, height));
        ImGui::TextDisabled("range %.6g .. %.6g", lowest, highest);
        ImGui::PopID();
    }
    if (!removed) return;
    for (std::size_t index = 0; index < session.runCount(); ++index) {
        ColumnPlots& each = session.run(index).columnPlots();
        for (std::size_t i = 0; i < each.plots().size(); ++i)
            if (each.plots()[i].column == *removed) each.remove(i--);
    }
}

}  // namespace substep::view
