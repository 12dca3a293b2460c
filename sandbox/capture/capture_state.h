#pragma once
/// The one place the capture command touches a running scene: start it with a capture's
/// settings, step it, read its state, sample its error measures and draw it. Everything else in
/// sandbox/capture/ works on the plain records below, so moving scenes onto another layer
/// (the ECS) changes this file pair only.

#include "capture/capture_script.h"
#include "render/render_scene.h"

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace substep::capture {

/// A body's pose (of its own frame, as scene files give it) and the velocities of its centre.
struct BodyState {
    std::string name;  ///< empty for an unnamed body
    std::array<double, 3> position{};
    std::array<double, 4> orientation{};  ///< w, x, y, z
    std::array<double, 3> velocity{};
    std::array<double, 3> angularVelocity{};
};

/// A joint's readout at the frame's last substep (DESIGN.md's CSV columns).
struct JointState {
    std::string name;
    double force = 0.0;   ///< N
    double torque = 0.0;  ///< N m
    double error = 0.0;   ///< m
};

struct SoftBodyState {
    std::string name;
    std::array<double, 3> centre{};  ///< centre of mass (m)
    double volume = 0.0;             ///< m³
};

/// Everything `state` compares at one frame: every body (static ones too) and every joint in the
/// world's storage order, and every soft body.
struct CaptureState {
    long long frame = 0;
    double time = 0.0;
    std::vector<BodyState> bodies;
    std::vector<JointState> joints;
    std::vector<SoftBodyState> softBodies;
};

/// The error measures `metrics` bounds, over every frame sampled so far.
struct RunMetrics {
    double maxJointError = 0.0;
    double energyDrift = 0.0;
    double penetration = 0.0;
};

class CaptureScene {
  public:
    /// Builds the capture's scene (built-in or file), its dt, substeps and iterations overrides
    /// and `set` knobs applied before frame 0, as `substep run` applies them. Throws InputError
    /// naming the script and `captures[i].set.NAME` for a knob the scene lacks, and the scene
    /// loader's errors for a bad scene file.
    CaptureScene(const CaptureSpec& spec, const std::string& scriptFile);
    ~CaptureScene();
    CaptureScene(CaptureScene&&) noexcept;
    CaptureScene& operator=(CaptureScene&&) noexcept;

    /// One frame of the scene's dt (its script's hook, then the world's step).
    void step();
    long long frame() const;
    bool isFinite() const;

    /// The current state into `state`, reusing its storage.
    void readState(CaptureState& state) const;

    /// Records the error measures of the current state (call at every frame from 0).
    void sampleMetrics();
    RunMetrics metrics() const;

    /// The current state to draw, framed for `aspect` as fixed at frame 0 (the capture's camera,
    /// else the scene's, else one that frames the bodies).
    render::RenderScene draw();

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace substep::capture
