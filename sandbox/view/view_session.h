#pragma once
/// What the viewer shows and steers: one scene's world, stepped in real time (or a frame at a
/// time), with the settings the panel edits and the histories it plots. Knows nothing of windows
/// or ImGui, so the scripted run and the interactive loop step it the same way.

#include "scene_drawing.h"
#include "scene_source.h"
#include "view/body_dragger.h"
#include "view/plot_history.h"

#include "render/render_scene.h"
#include "scene/scene.h"

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace substep::view {

/// The settings the panel edits. Substeps, iterations and gravity start from the scene's.
struct SessionControls {
    bool playing = true;
    float timeScale = 1.0f;  ///< simulated seconds per wall second
    int substeps = 20;
    int iterations = 1;
    float gravityY = -10.0f;  ///< m/s²; x and z stay the scene's
    DrawingOptions drawing;
};

class ViewSession {
  public:
    /// Builds `source`'s scene; `aspect` frames its camera. Throws what buildLabelledScene throws.
    ViewSession(SceneSource source, float aspect);

    /// Replaces the scene and resets the controls to its settings (keeping play state and layers).
    void load(SceneSource source);
    /// Rebuilds the current scene from its initial state, keeping the controls.
    void restart();
    /// Pushes substeps, iterations and gravity from controls() into the world.
    void applyControls();
    /// Redoes the overlays after a change of controls().drawing.
    void applyDrawingOptions();

    /// Real time: steps as many frames of the scene's dt as `wallSeconds` x time scale covers,
    /// at most a few per call so a slow scene slows down instead of freezing the window.
    /// Does nothing while paused or once the state turned non-finite.
    void advance(double wallSeconds);
    /// One frame of the scene's dt, paused or not.
    void stepOnce();

    /// Grabs the body under `ray` with a spring (body_dragger.h); false when none is there.
    bool grab(const Ray& ray) { return dragger_.grab(live_->world(), ray); }
    /// Moves the held spring's end along `ray`.
    void drag(const Ray& ray) { dragger_.drag(live_->world(), ray); }
    void release() { dragger_.release(live_->world()); }
    bool dragging() const { return dragger_.active(); }

    /// The current state to draw, seen through `camera`.
    render::RenderScene draw(const render::Camera& camera);

    /// The scene's named joints, for the panel's compliance sliders.
    const std::vector<std::pair<std::string, JointId>>& namedJoints() const { return live_->instance().namedJoints; }
    /// Sets a joint's attachment compliance α (m/N) live; a restart brings back the scene's.
    void setJointCompliance(JointId id, double compliance);

    SessionControls& controls() { return controls_; }
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

    long long frame() const { return live_->frame(); }
    double simulatedTime() const { return live_->time(); }
    bool finite() const { return finite_; }
    double lastStepMs() const { return lastStepMs_; }
    const PlotHistory& energyHistory() const { return energy_; }
    const PlotHistory& jointErrorHistory() const { return jointError_; }

  private:
    void rebuild(bool keepScript);
    void sample();

    SceneSource source_;
    float aspect_;
    SessionControls controls_;
    std::unique_ptr<LiveScene> live_;
    std::unique_ptr<SceneDrawing> drawing_;
    BodyDragger dragger_;
    double pendingSeconds_ = 0.0;  ///< simulated time owed to real time, less than one dt
    bool finite_ = true;
    double lastStepMs_ = 0.0;
    PlotHistory energy_{600};
    PlotHistory jointError_{600};
};

}  // namespace substep::view
