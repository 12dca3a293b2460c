#include "view/debug_layer_panel.h"

#include <imgui.h>

namespace substep::view {

bool drawBodyLayerControls(DrawingOptions& drawing) {
    bool changed = ImGui::Checkbox("boxes", &drawing.bounds);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("B: the box the broadphase pairs each body with");
    ImGui::SameLine();
    changed |= ImGui::Checkbox("centres", &drawing.centresOfMass);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("M: each moving body's centre of mass, along its principal axes");
    ImGui::SameLine();
    changed |= ImGui::Checkbox("velocities", &drawing.velocities);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("V: v at the centre of mass; omega along its axis with an arc of its sense");
    changed |= ImGui::SliderFloat("arrow scale", &drawing.arrowScale, 0.05f, 20.0f, "x %.2f",
                                  ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Forces, torques and velocities: times the scene's own scale");
    return changed;
}

bool toggleLayersByKey(const KeyActions& keys, DrawingOptions& drawing) {
    const auto toggle = [](int presses, bool& layer) {
        if (presses % 2 != 0) layer = !layer;
        return presses % 2 != 0;
    };
    bool changed = toggle(keys.toggleBounds, drawing.bounds);
    changed |= toggle(keys.toggleCentresOfMass, drawing.centresOfMass);
    changed |= toggle(keys.toggleVelocities, drawing.velocities);
    return changed;
}

}  // namespace substep::view
