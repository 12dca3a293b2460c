#include "view/view_panel.h"

#include "view/column_plot_panel.h"
#include "view/debug_layer_panel.h"

#include "scenes/scene_registry.h"

#include "ecs/components.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace substep::view {

namespace {

/// A plot of `history` with its latest value and range written over it. The range is padded so a
/// constant quantity draws as a flat line mid-plot rather than at an edge.
void plotHistory(const char* id, const PlotHistory& history, const char* format, float height = 70.0f) {
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
                     ImVec2(ImGui::GetContentRegionAvail().x, height));
    ImGui::TextDisabled("range %.6g .. %.6g", lowest, highest);
}

/// The scene script's own knobs (scene_script.h), under the solver settings: shown once, set in
/// every run.
void drawSceneKnobs(CompareSession& session) {
    SceneScript* script = session.first().script();
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
}

/// The scene script's readouts of one run.
void drawSceneReadouts(ViewSession& run) {
    SceneScript* script = run.script();
    if (script == nullptr) return;
    std::vector<SceneReadout> readouts;
    script->readouts(run.instance(), readouts);
    for (const SceneReadout& readout : readouts) {
        char value[64];
        std::snprintf(value, sizeof value, readout.format, readout.value);
        ImGui::TextWrapped("%s: %s", readout.label.c_str(), value);
    }
}

/// "20 x 1": a run's substeps x iterations, and ", start joints" under the start projection.
std::string splitLabel(const SessionControls& controls) {
    return std::to_string(controls.substeps) + " x " + std::to_string(controls.iterations) +
           (controls.jointProjection == JointProjection::Start ? ", start joints" : "");
}

/// One run's measures: its error plots (paper Fig. 10 and 11), its script's readouts and its
/// physics time with the step's stages.
void drawRunMeasures(ViewSession& run, bool compact) {
    const float plotHeight = compact ? 45.0f : 70.0f;
    if (!run.finite()) ImGui::TextColored(ImVec4(1.0f, 0.3f, 0.3f, 1.0f), "non-finite: restart");
    ImGui::TextUnformatted("total energy (J)");
    plotHistory("##energy", run.energyHistory(), "%.5g J", plotHeight);
    ImGui::TextUnformatted("largest joint error (m)");
    plotHistory("##joint_error", run.jointErrorHistory(), "%.3g m", plotHeight);
    if (const PlotHistory* elongation = run.chainElongationHistory()) {
        ImGui::TextUnformatted("chain elongation (L-L0)/L0");
        plotHistory("##elongation", *elongation, "%.3g", plotHeight);
    }
    drawSceneReadouts(run);
    const StepTimes& stages = run.world().stepTimes();
    if (compact) {
        ImGui::Text("physics %.2f ms/frame (solve %.2f)", run.lastStepMs(), stages.solve);
        return;
    }
    ImGui::Text("physics %.2f ms/frame", run.lastStepMs());
    ImGui::Text("  collision %.2f (broad %.2f, narrow %.2f)", stages.broadphase + stages.narrowphase,
                stages.broadphase, stages.narrowphase);
    ImGui::Text("  solve %.2f   velocity pass %.2f", stages.solve, stages.velocities);
    ImGui::Text("  integrate %.2f", stages.integrate);
}

/// In compare mode each run's measures sit in its own half of the window, at the bottom right
/// (the panel keeps the top left), under a line that splits the halves: each half then reads as
/// one side of the paper's Fig. 10, and a screenshot says which run is which.
void drawRunOverlays(CompareSession& session, const ViewArea& view) {
    if (!session.comparing()) return;
    for (std::size_t index = 0; index < session.runCount(); ++index) {
        const CompareSession::Part part = session.part(index, view);
        if (index > 0) {
            ImGui::GetBackgroundDrawList()->AddLine(ImVec2(part.left, view.top), ImVec2(part.left, view.top + view.height),
                                                    IM_COL32(20, 20, 24, 255), 3.0f);
        }
        ViewSession& run = session.run(index);
        // Inside its own half, at most half the view's height: the two never meet, and the
        // scene keeps the upper half.
        ImGui::SetNextWindowPos(ImVec2(part.left + part.width - 10.0f, view.top + view.height - 10.0f), ImGuiCond_Always,
                                ImVec2(1.0f, 1.0f));
        const float width = std::max(std::min(300.0f, part.width - 20.0f), 40.0f);
        ImGui::SetNextWindowSizeConstraints(ImVec2(width, 0.0f), ImVec2(width, view.height * 0.5f));
        ImGui::SetNextWindowBgAlpha(0.75f);
        char name[32];
        std::snprintf(name, sizeof name, "##run%zu", index);
        ImGui::Begin(name, nullptr,
                     ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoSavedSettings |
                         ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav);
        ImGui::TextWrapped("%s: %s (substeps x iterations)", index == 0 ? "left" : "right", splitLabel(run.controls()).c_str());
        drawRunMeasures(run, true);
        drawColumnPlots(session, run, 45.0f);
        ImGui::End();
    }
}

/// The selected body (a left click in the view): name, mass, pose, velocities and the joints on
/// it; in compare mode the first run's that has one.
void drawInspector(CompareSession& session) {
    for (std::size_t index = 0; index < session.runCount(); ++index) {
        const std::optional<BodyInspection> body = session.run(index).inspection();
        if (!body) continue;
        ImGui::Separator();
        ImGui::TextColored(ImVec4(1.0f, 0.85f, 0.1f, 1.0f), "selected: %s%s", body->name.c_str(),
                           session.comparing() ? (index == 0 ? " (left)" : " (right)") : "");
        if (body->isStatic) {
            ImGui::TextUnformatted("static (no mass)");
        } else {
            ImGui::Text("mass %.6g kg", body->mass);
            ImGui::TextWrapped("inertia %.4g %.4g %.4g kg m2 (principal)", body->inertia.x(), body->inertia.y(),
                               body->inertia.z());
        }
        ImGui::Text("contacts %d", body->contacts);
        ImGui::Text("position %.4g %.4g %.4g m", body->position.x(), body->position.y(), body->position.z());
        ImGui::TextWrapped("velocity %.4g %.4g %.4g m/s (|v| %.4g)", body->velocity.x(), body->velocity.y(),
                    body->velocity.z(), body->velocity.norm());
        ImGui::TextWrapped("angular velocity %.4g %.4g %.4g rad/s", body->angularVelocity.x(), body->angularVelocity.y(),
                    body->angularVelocity.z());
        constexpr std::size_t kMaxJoints = 8;
        for (std::size_t joint = 0; joint < body->joints.size() && joint < kMaxJoints; ++joint) {
            const JointInspection& each = body->joints[joint];
            ImGui::TextWrapped("joint %s: force %.4g N, torque %.4g N m, error %.3g m", each.name.c_str(), each.force,
                               each.torque, each.error);
        }
        if (body->joints.size() > kMaxJoints) ImGui::TextDisabled("... %zu joints in all", body->joints.size());
        return;
    }
}

/// The joint inspector (joint_inspector.h): a joint picked in a list or by a click near its
/// anchor: its bodies, force and torque, errors, limits and drive; in compare mode the first
/// run's.
void drawJointInspector(CompareSession& session) {
    ViewSession& run = session.first();
    const SceneInstance& scene = run.instance();
    if (scene.jointEntities.empty()) return;
    ImGui::Separator();
    const std::optional<JointDetails> joint = run.jointInspection();
    if (ImGui::BeginCombo("joint", joint ? joint->name.c_str() : "(click near an anchor)")) {
        constexpr std::size_t kMaxListed = 200;
        std::size_t listed = 0;
        for (const ecs::Entity entity : scene.jointEntities) {
            if (listed++ == kMaxListed) break;
            const ecs::Name* name = scene.registry.tryGet<ecs::Name>(entity);
            const std::string label = name ? name->value : "joint " + std::to_string(entity.index);
            ImGui::PushID(static_cast<int>(entity.index));
            if (ImGui::Selectable(label.c_str(), run.selectedJoint() == entity)) run.selectJoint(entity);
            ImGui::PopID();
        }
        ImGui::EndCombo();
    }
    if (!joint) return;
    ImGui::TextColored(ImVec4(0.2f, 0.9f, 1.0f, 1.0f), "%s '%s'", joint->type.c_str(), joint->name.c_str());
    ImGui::TextWrapped("bodies: '%s' and '%s'", joint->body0.c_str(), joint->body1.c_str());
    ImGui::Text("force %.5g N   torque %.5g N m", joint->force, joint->torque);
    ImGui::TextWrapped("error %.3g m, %.3g deg", joint->error, joint->angleError * 180.0 / M_PI);
    const double unit = joint->angular ? 180.0 / M_PI : 1.0;
    const char* unitName = joint->angular ? "deg" : "m";
    if (joint->hasCoordinate) ImGui::Text("%s %.4g %s", joint->angular ? "angle" : "offset", joint->coordinate * unit, unitName);
    if (joint->limits) {
        const std::optional<double> within = joint->withinLimits();
        ImGui::TextWrapped("limits %.4g .. %.4g %s: %s", joint->limits->lower * unit, joint->limits->upper * unit, unitName,
                           !within                                     ? "-"
                           : *within < 0.0 || *within > 1.0           ? "outside"
                           : *within < 0.02 || *within > 0.98         ? "at a limit"
                                                                       : "within");
        if (within) ImGui::ProgressBar(static_cast<float>(std::clamp(*within, 0.0, 1.0)), ImVec2(-1.0f, 0.0f), "");
    }
    if (joint->hasDrive)
        ImGui::TextWrapped("drive target %.4g %s, off by %.3g %s", joint->target * unit, unitName, joint->reach * unit,
                           unitName);
}

/// Up to `listed` lines of `entries` (each with describe()), the first in orange.
template <typename Entry>
void listEntries(const std::vector<Entry>& entries, std::size_t listed) {
    for (std::size_t i = 0; i < entries.size() && i < listed; ++i) {
        if (i == 0) ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.6f, 0.2f, 1.0f));
        ImGui::TextWrapped("%s", entries[i].describe().c_str());
        if (i == 0) ImGui::PopStyleColor();
    }
    if (entries.size() > listed) ImGui::TextDisabled("... %zu in all", entries.size());
}

/// One run's corrections of the last substep stepped by hand (correction_layer.h), largest
/// first: the position solve's, the soft bodies' stages, the velocity pass's. The view draws
/// them as arrows.
void drawRunCorrections(const ViewSession& run) {
    ImGui::Text("substep %d/%d corrections", run.correctionsSubstep(), run.correctionsSubsteps());
    const std::vector<CorrectionEntry>& entries = run.corrections();
    if (entries.empty() && run.softCorrections().empty()) {
        ImGui::TextDisabled("no constraint moved a body");
    } else {
        ImGui::TextDisabled("arrows: lime moves, white turns (scaled)");
        listEntries(entries, 12);
    }
    if (!run.softCorrections().empty()) {
        ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
        ImGui::TextWrapped("particles: lime elements, sand attachments, blue contacts, pink bounce and friction");
        ImGui::PopStyleColor();
        for (const SoftStageEntry& entry : run.softCorrections()) {
            const render::Colour colour = softStageColour(entry.stage);
            ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(colour.x(), colour.y(), colour.z(), 1.0f));
            ImGui::TextWrapped("%s", entry.describe().c_str());
            ImGui::PopStyleColor();
        }
    }
    ImGui::TextUnformatted("velocity pass (Eqs. 29-35)");
    if (run.velocityChanges().empty()) {
        ImGui::TextDisabled("no damping, bounce or friction changed a velocity");
    } else {
        ImGui::TextDisabled("arrows: pink velocity changes (scaled)");
        listEntries(run.velocityChanges(), 8);
    }
}

/// The corrections of every run; in compare mode each under its side's name.
void drawCorrectionList(CompareSession& session) {
    for (std::size_t index = 0; index < session.runCount(); ++index) {
        const ViewSession& run = session.run(index);
        if (run.correctionsSubstep() == 0) continue;
        ImGui::Separator();
        if (session.comparing()) {
            ImGui::TextColored(ImVec4(0.7f, 0.85f, 1.0f, 1.0f), "%s run (%d x %d)", index == 0 ? "left" : "right",
                               run.controls().substeps, run.controls().iterations);
            if (!session.steppedLastSubstep(index))
                ImGui::TextWrapped("not stepped: its next substep ends after the other run's; its last one's "
                                   "corrections:");
        }
        drawRunCorrections(run);
    }
}

/// The timeline (timeline.h): a slider over the kept frames, one frame back and forward.
void drawTimeline(const ViewSession& first, PanelRequests& requests) {
    if (!first.canRewind()) {
        ImGui::TextDisabled("timeline: this scene's script cannot be rewound");
        return;
    }
    const Timeline& timeline = first.timeline();
    if (ImGui::ArrowButton("##back", ImGuiDir_Left)) requests.scrubBy = -1;
    ImGui::SameLine();
    if (ImGui::ArrowButton("##forward", ImGuiDir_Right)) requests.scrubBy = 1;
    ImGui::SameLine();
    int frame = static_cast<int>(timeline.cursorFrame());
    if (ImGui::SliderInt("timeline", &frame, static_cast<int>(timeline.firstFrame()),
                         static_cast<int>(timeline.lastFrame()), "frame %d"))
        requests.scrubTo = frame;
    if (timeline.scrubbed())
        ImGui::TextWrapped("%lld later frames kept: play or step resumes from here and drops them",
                           timeline.lastFrame() - timeline.cursorFrame());
}

/// Frame rate, where the time goes (the swap is where a software rasteriser finishes drawing),
/// the real-time factor with a note when the scene cannot keep up, and the quality level.
void drawTiming(CompareSession& session, const ViewStatus& status, PanelRequests& requests) {
    if (status.stats != nullptr) {
        const FrameStats& stats = *status.stats;
        ImGui::Text("%.1f fps: frame %.1f ms", stats.fps(), stats.frameMs());
        ImGui::TextDisabled("physics %.1f  draw %.1f  swap %.1f ms", stats.physicsMs(), stats.renderMs(), stats.swapMs());
        const double factor = stats.realTimeFactor();
        if (factor >= 0.0) {
            ImGui::Text("real-time factor %.2f", factor);
            if (session.playback().playing && slowerThanRealTime(factor, session.playback().timeScale)) {
                ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.75f, 0.3f, 1.0f));
                ImGui::TextWrapped("slower than real time: a frame's physics and drawing take longer than the %.1f ms "
                                   "of simulated time it may step (at most 4 steps a frame)%s",
                                   1000.0 * session.source().description.dt,
                                   status.quality != render::QualityLevel::Light ? "; try the light quality" : "");
                ImGui::PopStyleColor();
            }
        }
    }
    int level = static_cast<int>(status.quality);
    const char* levels[] = {render::qualityName(render::QualityLevel::Light), render::qualityName(render::QualityLevel::Medium),
                            render::qualityName(render::QualityLevel::Full)};
    if (ImGui::Combo("quality", &level, levels, 3)) requests.quality = static_cast<render::QualityLevel>(level);
    if (ImGui::IsItemHovered()) {
        const render::RenderQuality quality = render::qualitySettings(status.quality);
        ImGui::SetTooltip("GL renderer: %s\n%d x MSAA, shadows %s (%d texels), spheres %d x %d\n%lld triangles drawn",
                          status.glRenderer.c_str(), quality.msaaSamples,
                          quality.shadows == render::ShadowMode::Off    ? "off"
                          : quality.shadows == render::ShadowMode::Hard ? "hard"
                                                                        : "soft",
                          quality.shadowMapSize, quality.sphereRings, quality.sphereSegments, status.triangles);
    }
    if (!status.notice.empty()) ImGui::TextWrapped("%s", status.notice.c_str());
}

}  // namespace

PanelRequests ViewPanel::draw(CompareSession& session, const ViewStatus& status, const ViewArea& view,
                              const std::string& loadError) {
    PanelRequests requests;
    Playback& playback = session.playback();
    ViewSession& first = session.first();
    SessionControls& shared = first.controls();  // gravity and the debug layers: every run's
    const bool comparing = session.comparing();
    drawRunOverlays(session, view);
    // Docked at the left edge, full height, beside the view (view_layout.h): it never covers
    // the scene, and scrolls when its content is taller than the window.
    ImGui::SetNextWindowPos(ImVec2(0.0f, 0.0f), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(view.left, ImGui::GetIO().DisplaySize.y), ImGuiCond_Always);
    ImGui::Begin("Substep", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
    ImGui::PushItemWidth(ImGui::GetContentRegionAvail().x * 0.6f);

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
    if (!loadError.empty()) {
        ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.4f, 0.3f, 1.0f));
        ImGui::TextWrapped("%s", loadError.c_str());
        ImGui::PopStyleColor();
    }

    // Time.
    ImGui::Separator();
    if (ImGui::Button(playback.playing ? "pause" : "play")) playback.playing = !playback.playing;
    ImGui::SameLine();
    if (ImGui::Button("step")) requests.step = true;
    ImGui::SameLine();
    if (ImGui::Button("substep")) requests.substep = true;
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("One substep (key . or Shift+Right): what each constraint corrected is drawn and listed");
    ImGui::SameLine();
    if (ImGui::Button("restart")) requests.restart = true;
    ImGui::SameLine();
    if (ImGui::Button("camera")) requests.resetCamera = true;
    ImGui::SameLine();
    ImGui::TextDisabled("(F1: keys)");
    if (first.frameOpen()) {
        ImGui::Text("frame %lld, substep %d/%d   t = %.3f s", first.frame(), first.frameSubstepsDone(),
                    first.frameSubsteps(), first.simulatedTime());
    } else {
        ImGui::Text("frame %lld   t = %.3f s", first.frame(), first.simulatedTime());
    }
    ImGui::SliderFloat("time scale", &playback.timeScale, 0.05f, 4.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
    drawTimeline(first, requests);
    drawTiming(session, status, requests);

    // Solver: one column per run, each with its own substeps and iterations.
    ImGui::Separator();
    bool compare = comparing;
    if (ImGui::Checkbox("compare side by side", &compare)) requests.compare = compare;
    if (ImGui::IsItemHovered()) {
        ImGui::SetTooltip("The same scene twice with different solver settings, stepped in lockstep\n"
                          "(paper Fig. 10: 20 substeps x 1 iteration against 1 x 20)");
    }
    const int runs = static_cast<int>(session.runCount());
    if (ImGui::BeginTable("solver", runs)) {
        for (int index = 0; index < runs; ++index) {
            ImGui::TableNextColumn();
            ImGui::PushID(index);
            SessionControls& controls = session.run(static_cast<std::size_t>(index)).controls();
            if (comparing) ImGui::TextUnformatted(index == 0 ? "left" : "right");
            ImGui::PushItemWidth(comparing ? -1.0f : ImGui::GetContentRegionAvail().x * 0.6f);
            requests.controlsChanged |= ImGui::SliderInt(comparing ? "##substeps" : "substeps", &controls.substeps, 1,
                                                         200, comparing ? "%d substeps" : "%d",
                                                         ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp);
            requests.controlsChanged |= ImGui::SliderInt(comparing ? "##iterations" : "iterations", &controls.iterations,
                                                         1, 50, comparing ? "%d iterations" : "%d",
                                                         ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp);
            // Joint directions: the paper's (current state) or the substep's start (energy kept).
            int projection = controls.jointProjection == JointProjection::Start ? 1 : 0;
            if (ImGui::Combo(comparing ? "##joints" : "joints", &projection, "paper\0start\0")) {
                controls.jointProjection =
                    projection == 1 ? JointProjection::Start : JointProjection::Paper;
                requests.controlsChanged = true;
            }
            if (ImGui::IsItemHovered())
                ImGui::SetTooltip("Joint projection: paper = directions on the current state;\n"
                                  "start = on the substep's start poses (keeps a pendulum's "
                                  "energy)");
            // Restitution: sweeps of two-body collisions (any listing order) or Eq. 34 alone.
            int restitution = controls.sweptRestitution ? 0 : 1;
            if (ImGui::Combo(comparing ? "##restitution" : "restitution", &restitution, "swept\0paper\0")) {
                controls.sweptRestitution = restitution == 0;
                requests.controlsChanged = true;
            }
            if (ImGui::IsItemHovered())
                ImGui::SetTooltip("Restitution: swept = two-body collisions swept through touching\n"
                                  "bodies, the same in any listing order; paper = Eq. 34 alone");
            ImGui::PopItemWidth();
            ImGui::PopID();
        }
        ImGui::EndTable();
    }
    requests.controlsChanged |=
        ImGui::SliderFloat("gravity y", &shared.gravityY, -30.0f, 30.0f, "%.2f m/s^2", ImGuiSliderFlags_AlwaysClamp);

    drawSceneKnobs(session);

    // Debug layers.
    ImGui::Separator();
    requests.drawingChanged |= ImGui::Checkbox("joints", &shared.drawing.jointFrames);
    ImGui::SameLine();
    requests.drawingChanged |= ImGui::Checkbox("forces", &shared.drawing.jointForces);
    ImGui::SameLine();
    requests.drawingChanged |= ImGui::Checkbox("torques", &shared.drawing.jointTorques);
    ImGui::SameLine();
    requests.drawingChanged |= ImGui::Checkbox("contacts", &shared.drawing.contacts);
    requests.drawingChanged |= drawBodyLayerControls(shared.drawing);

    // Per-joint compliance (the attachment's α), live in every run; a restart brings back the
    // scene's.
    if (!first.namedJoints().empty() && ImGui::CollapsingHeader("joint compliance (m/N)")) {
        constexpr size_t kMaxListed = 64;  // chains of 100 links list their first 64
        size_t listed = 0;
        for (const auto& [name, id] : first.namedJoints()) {
            if (listed++ == kMaxListed) break;
            float compliance = static_cast<float>(first.jointCompliance(id));
            if (ImGui::SliderFloat(name.c_str(), &compliance, 0.0f, 1.0f, "%.2e", ImGuiSliderFlags_Logarithmic)) {
                session.setJointCompliance(id, compliance);
            }
        }
    }

    drawInspector(session);
    drawJointInspector(session);
    drawCorrectionList(session);

    // Measures; in compare mode each run's are drawn in its half of the window instead.
    if (!comparing) {
        ImGui::Separator();
        drawRunMeasures(first, false);
    }
    // Plots of any column the CSV would have; in compare mode drawn in each run's half.
    ImGui::Separator();
    columnPlotPanel_.drawPicker(session);
    if (!comparing) drawColumnPlots(session, first, 70.0f);

    ImGui::Separator();
    ImGui::TextDisabled("F1: every key; Tab hides the panel");
    ImGui::TextDisabled("left drag orbits, click selects,");
    ImGui::TextDisabled("Ctrl + left drag grabs a body");
    ImGui::PopItemWidth();
    ImGui::End();
    return requests;
}

}  // namespace substep::view
