#include "view/view_panel.h"

#include "scenes/scene_registry.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace substep::view {

namespace {

/// A plot of `history` with its latest value and range written over it. The range is padded so a
/// constant quantity draws as a flat line mid-plot rather than at an edge.
void plotHistory(const char* id, const PlotHistory& history, const char* format) {
    auto [lowest, highest] = history.range();
    // Padded so a constant quantity draws as a flat line mid-plot: a float range of zero width
    // (or one lost in rounding, 1e-6 around 20 J) draws nothing at all.
    const float magnitude = std::max(std::abs(lowest), std::abs(highest));
    const float pad = std::max({0.05f * (highest - lowest), 1e-4f * magnitude, 1e-9f});
    char overlay[96];
    std::snprintf(overlay, sizeof overlay, format, history.latest());
    // Until the ring is full its samples are the first count() slots, oldest first.
    const bool full = history.count() == static_cast<std::size_t>(history.size());
    const int count = full ? history.size() : static_cast<int>(history.count());
    ImGui::PlotLines(id, history.data(), count, full ? history.offset() : 0, overlay, lowest - pad, highest + pad,
                     ImVec2(ImGui::GetContentRegionAvail().x, 70.0f));
    ImGui::TextDisabled("range %.6g .. %.6g", lowest, highest);
}

/// The scene script's own knobs and readouts (scene_script.h), under the solver settings.
void drawSceneControls(ViewSession& session) {
    SceneScript* script = session.script();
    if (script == nullptr) return;
    ImGui::Separator();
    ImGui::TextUnformatted("scene");
    const std::span<SceneKnob> knobs = script->knobs();
    for (std::size_t index = 0; index < knobs.size(); ++index) {
        const SceneKnob& knob = knobs[index];
        switch (knob.kind) {
            case SceneKnob::Kind::Toggle: {
                bool on = knob.value != 0.0;
                if (ImGui::Checkbox(knob.label.c_str(), &on)) session.setKnob(index, on ? 1.0 : 0.0);
                break;
            }
            case SceneKnob::Kind::Slider: {
                float value = static_cast<float>(knob.value);
                const ImGuiSliderFlags flags =
                    ImGuiSliderFlags_AlwaysClamp | (knob.logarithmic ? ImGuiSliderFlags_Logarithmic : 0);
                if (ImGui::SliderFloat(knob.label.c_str(), &value, static_cast<float>(knob.min),
                                       static_cast<float>(knob.max), knob.format, flags)) {
                    session.setKnob(index, value);
                }
                break;
            }
            case SceneKnob::Kind::Choice: {
                const int current = static_cast<int>(knob.value);
                if (ImGui::BeginCombo(knob.label.c_str(), knob.choices.at(static_cast<std::size_t>(current)).c_str())) {
                    for (std::size_t choice = 0; choice < knob.choices.size(); ++choice) {
                        if (ImGui::Selectable(knob.choices[choice].c_str(), static_cast<int>(choice) == current)) {
                            session.setKnob(index, static_cast<double>(choice));
                        }
                    }
                    ImGui::EndCombo();
                }
                break;
            }
        }
    }
    std::vector<SceneReadout> readouts;
    script->readouts(session.instance(), readouts);
    for (const SceneReadout& readout : readouts) {
        char value[64];
        std::snprintf(value, sizeof value, readout.format, readout.value);
        ImGui::Text("%s: %s", readout.label.c_str(), value);
    }
}

}  // namespace

PanelRequests ViewPanel::draw(ViewSession& session, const FrameTimes& times, const std::string& loadError) {
    PanelRequests requests;
    SessionControls& controls = session.controls();
    ImGui::SetNextWindowPos(ImVec2(10.0f, 10.0f), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(360.0f, 0.0f), ImGuiCond_FirstUseEver);
    ImGui::Begin("Substep");

    // Scene: the built-ins in a combo, any scene file by path.
    const std::string& label = session.source().label;
    if (ImGui::BeginCombo("scene", label.c_str())) {
        for (const SceneEntry& entry : builtinScenes()) {
            const std::string name(entry.name);
            if (ImGui::Selectable(name.c_str(), name == label)) requests.loadScene = name;
            if (ImGui::IsItemHovered()) {
                ImGui::SetTooltip("%.*s", static_cast<int>(entry.description.size()), entry.description.data());
            }
        }
        ImGui::EndCombo();
    }
    ImGui::InputTextWithHint("##path", "path/to/scene.json", path_, sizeof path_);
    ImGui::SameLine();
    if (ImGui::Button("open") && path_[0] != '\0') requests.loadScene = std::string(path_);
    if (!loadError.empty()) ImGui::TextColored(ImVec4(1.0f, 0.4f, 0.3f, 1.0f), "%s", loadError.c_str());

    // Time.
    ImGui::Separator();
    if (ImGui::Button(controls.playing ? "pause" : "play")) controls.playing = !controls.playing;
    ImGui::SameLine();
    if (ImGui::Button("step")) requests.step = true;
    ImGui::SameLine();
    if (ImGui::Button("restart")) requests.restart = true;
    ImGui::SameLine();
    ImGui::TextDisabled("(space, S, R)");
    ImGui::Text("frame %lld   t = %.3f s", session.frame(), session.simulatedTime());
    if (!session.finite()) ImGui::TextColored(ImVec4(1.0f, 0.3f, 0.3f, 1.0f), "state turned non-finite: restart");
    ImGui::SliderFloat("time scale", &controls.timeScale, 0.05f, 4.0f, "%.2f", ImGuiSliderFlags_Logarithmic);

    // Solver.
    ImGui::Separator();
    requests.controlsChanged |= ImGui::SliderInt("substeps", &controls.substeps, 1, 200, "%d",
                                                 ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp);
    requests.controlsChanged |= ImGui::SliderInt("iterations", &controls.iterations, 1, 50, "%d",
                                                 ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp);
    requests.controlsChanged |=
        ImGui::SliderFloat("gravity y", &controls.gravityY, -30.0f, 30.0f, "%.2f m/s^2", ImGuiSliderFlags_AlwaysClamp);

    drawSceneControls(session);

    // Debug layers.
    ImGui::Separator();
    requests.drawingChanged |= ImGui::Checkbox("joints", &controls.drawing.jointFrames);
    ImGui::SameLine();
    requests.drawingChanged |= ImGui::Checkbox("forces", &controls.drawing.jointForces);
    ImGui::SameLine();
    requests.drawingChanged |= ImGui::Checkbox("contacts", &controls.drawing.contacts);

    // Per-joint compliance (the attachment's α), live; a restart brings back the scene's.
    if (!session.namedJoints().empty() && ImGui::CollapsingHeader("joint compliance (m/N)")) {
        constexpr size_t kMaxListed = 64;  // chains of 100 links list their first 64
        size_t listed = 0;
        for (const auto& [name, id] : session.namedJoints()) {
            if (listed++ == kMaxListed) break;
            float compliance = static_cast<float>(session.world().joint(id).compliance);
            if (ImGui::SliderFloat(name.c_str(), &compliance, 0.0f, 1.0f, "%.2e", ImGuiSliderFlags_Logarithmic)) {
                session.setJointCompliance(id, compliance);
            }
        }
    }

    // Measures.
    ImGui::Separator();
    ImGui::TextUnformatted("total energy (J)");
    plotHistory("##energy", session.energyHistory(), "%.5g J");
    ImGui::TextUnformatted("largest joint error (m)");
    plotHistory("##joint_error", session.jointErrorHistory(), "%.3g m");

    ImGui::Separator();
    ImGui::Text("physics %.2f ms   render %.2f ms", session.lastStepMs(), times.renderMs);
    const StepTimes& stages = session.world().stepTimes();
    ImGui::Text("  collision %.2f (broad %.2f, narrow %.2f)", stages.broadphase + stages.narrowphase,
                stages.broadphase, stages.narrowphase);
    ImGui::Text("  solve %.2f   velocity pass %.2f", stages.solve, stages.velocities);
    ImGui::Text("  integrate %.2f", stages.integrate);
    ImGui::Text("frame %.1f ms (%.0f fps)", times.frameMs, times.frameMs > 0.0 ? 1000.0 / times.frameMs : 0.0);
    ImGui::TextDisabled("mouse: left drag a body or orbit,");
    ImGui::TextDisabled("right/middle pan, wheel zoom");
    ImGui::End();
    return requests;
}

}  // namespace substep::view
