#pragma once
/// The runs the viewer shows and paces in real time: one run of a scene, or in compare mode the
/// paper's Fig. 10 — the same scene twice, side by side, with different solver settings (20
/// substeps x 1 iteration against 1 x 20 by default). Both runs start from the same source, step
/// the same dt in lockstep and share the play state, time scale, gravity, debug layers, script
/// knobs and joint edits; each keeps its own substeps and iterations, its error plots and its
/// physics time. The frame loop and the panel drive this the same way in both modes: a loop over
/// the runs, each drawn in its own part of the window.

#include "view/view_layout.h"
#include "view/view_session.h"

#include "render/render_target.h"

#include <array>
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace substep::view {

/// One run's solver settings: substeps per frame, iterations per substep and, when given, the
/// joint projection (WorldSettings::jointProjection; none: the scene's).
struct SolverSplit {
    int substeps = 20;
    int iterations = 1;
    std::optional<JointProjection> jointProjection;
    friend bool operator==(const SolverSplit&, const SolverSplit&) = default;
};

/// The left and right runs' splits.
using CompareSplits = std::array<SolverSplit, 2>;

/// The paper's Fig. 10 comparison: 20 substeps of 1 iteration against 1 step of 20 iterations,
/// the same solver work per frame.
inline constexpr CompareSplits kPaperCompareSplits{{{20, 1}, {1, 20}}};

/// Reads "SUBSTEPSxITERATIONS,SUBSTEPSxITERATIONS" (e.g. "20x1,1x20"), each count a whole number
/// in [1, 1000], each split optionally followed by ":paper" or ":start" (the joint projection,
/// e.g. "20x1:paper,20x1:start"); nullopt when the text is not that.
std::optional<CompareSplits> parseCompareSplits(const std::string& text);

/// Shared by the runs: whether they play, and how fast against the wall clock.
struct Playback {
    bool playing = true;
    float timeScale = 1.0f;  ///< simulated seconds per wall second
};

class CompareSession {
  public:
    /// One run of `source`; `aspect` is the window's. Throws what ViewSession throws.
    CompareSession(SceneSource source, float aspect);

    /// Compare mode on with `splits` (left, right), or off (nullopt: one run, with the scene's
    /// own substeps and iterations). Either way the runs start again from the scene's start;
    /// gravity and the debug layers are kept.
    void compare(std::optional<CompareSplits> splits);
    bool comparing() const { return runs_.size() == 2; }
    /// The splits the runs have now (or last had, when compare mode is off).
    const CompareSplits& splits() const { return splits_; }

    /// Replaces the scene in every run. In compare mode the runs keep their splits.
    void load(SceneSource source);
    /// Every run from its initial state again, keeping the controls.
    void restart();

    /// Real time: steps every run by as many frames of the scene's dt as `wallSeconds` x time
    /// scale covers, at most a few per call so a slow scene slows down instead of freezing the
    /// window. Does nothing while paused; pauses once no run is finite any more.
    void advance(double wallSeconds);
    /// One frame of the scene's dt in every run (a run whose state turned non-finite stays put).
    void stepOnce();
    /// Pauses and steps one substep, drawing what each constraint corrected
    /// (ViewSession::stepSubstep). In compare mode the run with the most substeps per frame
    /// steps one, and each other run the substeps that end by then, so the runs stay at the same
    /// moment and end each frame together. Playing again stops the recording.
    void stepSubstep();
    /// Whether run `index` stepped a substep at the last stepSubstep (in compare mode a run
    /// with fewer substeps waits for the moment its next one ends).
    bool steppedLastSubstep(std::size_t index) const {
        return index < steppedLastSubstep_.size() && steppedLastSubstep_[index];
    }
    /// Pauses and moves every run by `frames` through its timeline (timeline.h): back through
    /// the kept states, forward through them and, past the newest, by new steps.
    void scrubBy(long long frames);
    /// Pauses and shows frame `frame` of every run's timeline (clamped to what it keeps).
    void scrubTo(long long frame);

    /// Copies the shared controls (gravity, the first run's) into every run and applies each
    /// run's controls to its world; each run's splits() follow its substeps and iterations.
    void applyControls();
    /// Copies the first run's debug layers into every run and redoes the overlays.
    void applyDrawingOptions();
    /// Sets script knob `index` in every run. In compare mode each run keeps its own substeps and
    /// iterations, even when the knob switches the solver: the split is what is compared.
    void setKnob(std::size_t index, double value);
    /// Sets a joint's compliance in every run (the runs are built alike, so entities agree).
    void setJointCompliance(ecs::Entity joint, double compliance);

    Playback& playback() { return playback_; }
    std::size_t runCount() const { return runs_.size(); }
    ViewSession& run(std::size_t index) { return *runs_[index]; }
    const ViewSession& run(std::size_t index) const { return *runs_[index]; }
    /// The first run: the scene, frame and shared controls the panel shows once.
    ViewSession& first() { return *runs_.front(); }
    const SceneSource& source() const { return runs_.front()->source(); }
    /// The camera the scene starts from, framed for one run's part of the window.
    const render::Camera& startCamera() const { return runs_.front()->startCamera(); }

    /// The pixels run `index` is drawn in: its share of `view` (the window's area beside the
    /// panel, view_layout.h), side by side left to right, full height; `view` is that area's
    /// pixels in the window's framebuffer.
    render::RenderTarget target(std::size_t index, const render::RenderTarget& view) const;
    /// The horizontal span of `area` (ImGui's window coordinates, for the mouse) that run
    /// `index` is drawn in.
    struct Part {
        float left = 0.0f;
        float width = 0.0f;
    };
    Part part(std::size_t index, const ViewArea& area) const;
    /// The run drawn under window x coordinate `x` of `area`.
    std::size_t runAt(float x, const ViewArea& area) const;

    /// The run a body is held in (dragged with the mouse), if any.
    std::optional<std::size_t> dragging() const;

  private:
    void applySplits();

    float aspect_;
    Playback playback_;
    CompareSplits splits_ = kPaperCompareSplits;
    std::vector<std::unique_ptr<ViewSession>> runs_;
    double pendingSeconds_ = 0.0;  ///< simulated time owed to real time, less than one dt
    std::vector<bool> steppedLastSubstep_;  ///< per run, at the last stepSubstep
};

}  // namespace substep::view
