#pragma once
/// One run of a scene in the viewer: its world, stepped a frame at a time, with the settings the
/// panel edits and the histories it plots. Knows nothing of windows or ImGui, so the scripted
/// run and the interactive loop step it the same way. The viewer shows one run, or two in
/// compare mode (compare_session.h, which also paces them in real time).

#include "error_measures.h"
#include "scene_drawing.h"
#include "scene_source.h"
#include "view/body_dragger.h"
#include "view/body_inspector.h"
#include "view/column_plots.h"
#include "view/correction_layer.h"
#include "view/joint_inspector.h"
#include "view/plot_history.h"
#include "view/timeline.h"

#include "render/render_scene.h"
#include "scene/scene.h"

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace substep::view {

/// The settings of one run the panel edits. Substeps, iterations and gravity start from the
/// scene's.
struct SessionControls {
    int substeps = 20;
    int iterations = 1;
    JointProjection jointProjection = JointProjection::Paper;  ///< WorldSettings::jointProjection
    bool sweptRestitution = WorldSettings{}.sweptRestitution;  ///< WorldSettings::sweptRestitution
    float gravityY = -10.0f;  ///< m/s²; x and z stay the scene's
    DrawingOptions drawing;
};

class ViewSession {
  public:
    /// Builds `source`'s scene; `aspect` frames its camera. Throws what buildLabelledScene throws.
    ViewSession(SceneSource source, float aspect);

    /// Replaces the scene and resets the controls to its settings (keeping the debug layers).
    void load(SceneSource source);
    /// Rebuilds the current scene from its initial state, keeping the controls.
    void restart();
    /// Pushes substeps, iterations and gravity from controls() into the world.
    void applyControls();
    /// Redoes the overlays after a change of controls().drawing (cheap: camera, ground and the
    /// scene's arrow scales stay as the build fixed them).
    void applyDrawingOptions();

    /// One frame of the scene's dt; does nothing once the state turned non-finite. A frame left
    /// open by stepSubstep is finished instead (the rest of its substeps), as whole-frame
    /// stepping would have left it.
    void stepOnce();
    /// One substep of the current frame (beginning it if none is open), with each constraint's
    /// corrections recorded for corrections(); the frame's last substep also ends the frame and
    /// keeps it in the timeline. Nothing once the state turned non-finite.
    void stepSubstep();
    /// Stops recording corrections (the run plays again) and forgets the last ones.
    void stopRecordingCorrections();
    /// The last stepped substep's corrections, largest first (correction_layer.h); empty unless
    /// substeps are being stepped.
    const std::vector<CorrectionEntry>& corrections() const { return corrections_; }
    /// The same substep's velocity pass, largest first (correction_layer.h).
    const std::vector<VelocityEntry>& velocityChanges() const { return velocityChanges_; }
    /// The same substep's soft-body stages, each soft body's share (correction_layer.h).
    const std::vector<SoftStageEntry>& softCorrections() const { return softCorrections_; }
    /// The substep the corrections belong to and the frame's substeps (0, 0 without any).
    int correctionsSubstep() const { return correctionsSubstep_; }
    int correctionsSubsteps() const { return correctionsSubsteps_; }
    /// Whether a frame is open, with its substeps done and in all (live_scene.h).
    bool frameOpen() const { return live_->frameOpen(); }
    int frameSubstepsDone() const { return live_->frameSubstepsDone(); }
    int frameSubsteps() const { return live_->frameSubsteps(); }

    /// Grabs the body under `ray` (body_dragger.h): a dynamic one with a spring, a static
    /// non-colliding one directly. False when none is there.
    /// Each of these changes components; the world follows at once (LiveScene::sync), so what
    /// is drawn and measured agrees while the scene is paused.
    bool grab(const Ray& ray);
    /// Moves the held spring's end, or the held static body, along `ray`.
    void drag(const Ray& ray);
    void release();
    bool dragging() const { return dragger_.active(); }

    /// Selects the body under `ray` for the inspector (body_inspector.h), or clears the
    /// selection when the ray meets none. True when a body is selected.
    /// With `radiansPerPixel` (the view's vertical field of view over its height in pixels) a
    /// ray passing within 12 pixels of a joint's anchor selects that joint instead.
    bool select(const Ray& ray, double radiansPerPixel = 0.0);
    /// Selects a joint for the joint inspector (joint_inspector.h), clearing the body's.
    void selectJoint(ecs::Entity joint);
    /// The selected joint as it is now; nullopt with none.
    std::optional<JointDetails> jointInspection();
    std::optional<ecs::Entity> selectedJoint() const { return selectedJoint_; }
    /// The selected body as it is now; nullopt with none (a restart or load clears it).
    std::optional<BodyInspection> inspection();

    /// The current state to draw, seen through `camera`, the selected body outlined.
    render::RenderScene draw(const render::Camera& camera);

    /// The scene's named joints, for the panel's compliance sliders.
    const std::vector<std::pair<std::string, ecs::Entity>>& namedJoints() const { return namedJoints_; }
    /// A joint's attachment compliance α (m/N), as its component holds it.
    double jointCompliance(ecs::Entity joint) const;
    /// Sets a joint's attachment compliance α (m/N) live; a restart brings back the scene's.
    void setJointCompliance(ecs::Entity joint, double compliance);

    SessionControls& controls() { return controls_; }
    const SessionControls& controls() const { return controls_; }
    const SceneSource& source() const { return source_; }
    /// The camera the scene starts from (its own, else one framing the bodies).
    const render::Camera& startCamera() const { return drawing_->camera(); }
    const World& world() const { return live_->world(); }
    /// The scene's script (its knobs and readouts for the panel), or nullptr.
    SceneScript* script() { return live_->script(); }
    const SceneInstance& instance() const { return live_->instance(); }
    /// Sets knob `index` of the script to `value` and applies it; substeps and iterations follow
    /// when the knob changed them.
    void setKnob(std::size_t index, double value);

    /// The run's last seconds, a state per frame (timeline.h). Restarts, loads and edits that
    /// the kept states did not see (a knob, a compliance, a grab and its release) start a new
    /// history from the current frame.
    const Timeline& timeline() const { return timeline_; }
    /// Whether the run can be rewound exactly (its script can be copied; live_scene.h).
    bool canRewind() const { return live_->canSnapshot(); }
    /// Shows the kept state of `frame` (clamped to the timeline's range): the world, the script
    /// and the frame count as they were, so that stepping from it replays the run. Nothing
    /// while a body is held or the scene cannot be rewound; true when the state changed.
    bool scrubTo(long long frame);

    long long frame() const { return live_->frame(); }
    double simulatedTime() const { return live_->time(); }
    bool finite() const { return finite_; }
    double lastStepMs() const { return lastStepMs_; }
    const PlotHistory& energyHistory() const { return energy_; }
    const PlotHistory& jointErrorHistory() const { return jointError_; }
    /// The chain's relative elongation (L − L0) / L0 (error_measures.h; paper Fig. 11), when the
    /// built-in scene has a chain measure; else nullptr.
    const PlotHistory* chainElongationHistory() const { return chainMeasure_ ? &chainElongation_ : nullptr; }
    /// Plots of any column `run --csv` would write (column_plots.h), following the timeline.
    ColumnPlots& columnPlots() { return columnPlots_; }
    const ColumnPlots& columnPlots() const { return columnPlots_; }

  private:
    void rebuild(bool keepScript);
    /// A new SceneDrawing from a fresh build of the scene (its camera, ground and scales).
    void makeDrawing();
    void sample();
    /// Forgets the kept states and keeps the current one as the first.
    void restartHistory();

    SceneSource source_;
    float aspect_;
    SessionControls controls_;
    std::unique_ptr<LiveScene> live_;
    std::unique_ptr<SceneDrawing> drawing_;
    BodyDragger dragger_;
    std::optional<ecs::Entity> selected_;  ///< the inspector's body
    std::optional<ecs::Entity> selectedJoint_;  ///< the joint inspector's joint
    bool recordingCorrections_ = false;
    std::vector<CorrectionEntry> corrections_;
    std::vector<VelocityEntry> velocityChanges_;
    std::vector<SoftStageEntry> softCorrections_;
    int correctionsSubstep_ = 0;
    int correctionsSubsteps_ = 0;
    /// After a frame ended: its measures sampled and its state kept in the timeline.
    void frameEnded();
    /// Reads the world's record of the last substep into corrections().
    void readCorrections();
    /// Measures the chain's elongation as `substep sweep` does; null without a chain.
    std::unique_ptr<ErrorRecorder> chainMeasure_;
    std::vector<std::pair<std::string, ecs::Entity>> namedJoints_;  ///< of the current build
    bool finite_ = true;
    double lastStepMs_ = 0.0;
    PlotHistory energy_{600};
    PlotHistory jointError_{600};
    PlotHistory chainElongation_{600};
    ColumnPlots columnPlots_;
    Timeline timeline_;
};

}  // namespace substep::view
