#include "view/view_session.h"

#include <algorithm>
#include <chrono>

namespace substep::view {

namespace {

/// Frames one advance() may step. A scene slower than real time then runs slow but the window
/// stays responsive, instead of owing ever more steps (the "spiral of death").
constexpr int kMaxFramesPerAdvance = 4;

SessionControls controlsOf(const SceneDescription& description, const SessionControls& kept) {
    SessionControls controls = kept;
    controls.substeps = description.substeps;
    controls.iterations = description.iterations;
    controls.gravityY = static_cast<float>(description.gravity.y());
    return controls;
}

}  // namespace

ViewSession::ViewSession(SceneSource source, float aspect) : source_(std::move(source)), aspect_(aspect) {
    controls_ = controlsOf(source_.description, controls_);
    rebuild();
}

void ViewSession::load(SceneSource source) {
    source_ = std::move(source);
    controls_ = controlsOf(source_.description, controls_);
    rebuild();
}

void ViewSession::restart() { rebuild(); }

void ViewSession::rebuild() {
    dragger_.forget();  // its spring goes with the old world
    instance_ = buildLabelledScene(source_.description, source_.label);
    applyControls();
    applyDrawingOptions();
    frame_ = 0;
    pendingSeconds_ = 0.0;
    finite_ = instance_.world.isFinite();
    lastStepMs_ = 0.0;
    energy_.clear();
    jointError_.clear();
    sample();
}

void ViewSession::setJointCompliance(JointId id, double compliance) {
    if (instance_.world.isValid(id) && compliance >= 0.0) instance_.world.joint(id).compliance = compliance;
}

void ViewSession::applyControls() {
    WorldSettings settings = instance_.world.settings();
    settings.substeps = controls_.substeps;
    settings.iterations = controls_.iterations;
    settings.gravity.y() = controls_.gravityY;
    settings.measureTime = true;  // the panel's stage breakdown
    instance_.world.setSettings(settings);
}

void ViewSession::applyDrawingOptions() {
    // SceneDrawing fixes its camera, ground and force scale from the state it is made from; a
    // fresh build of the scene gives the same ones as at the start, whatever the world did since.
    const SceneInstance initial = buildLabelledScene(source_.description, source_.label);
    drawing_ = std::make_unique<SceneDrawing>(source_.description, initial.world, aspect_, controls_.drawing);
}

void ViewSession::advance(double wallSeconds) {
    if (!controls_.playing || !finite_) {
        pendingSeconds_ = 0.0;
        return;
    }
    const double dt = source_.description.dt;
    pendingSeconds_ += wallSeconds * controls_.timeScale;
    int frames = 0;
    while (pendingSeconds_ >= dt && frames < kMaxFramesPerAdvance && finite_) {
        stepOnce();
        pendingSeconds_ -= dt;
        ++frames;
    }
    // What could not be stepped now is dropped, not carried: the scene runs slow, then catches
    // nothing up in a burst.
    if (frames == kMaxFramesPerAdvance) pendingSeconds_ = 0.0;
}

void ViewSession::stepOnce() {
    if (!finite_) return;
    const auto start = std::chrono::steady_clock::now();
    instance_.world.step(source_.description.dt);
    lastStepMs_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    ++frame_;
    finite_ = instance_.world.isFinite();
    if (!finite_) {
        controls_.playing = false;
        return;
    }
    sample();
}

void ViewSession::sample() {
    // The plots measure the scene, not the hand pulling it: the drag spring's stretch and stored
    // energy are left out (the work it does still shows as a change of the scene's energy).
    const World& world = instance_.world;
    const std::optional<JointId> spring = dragger_.joint();
    double energy = world.energies().total();
    double jointError = 0.0;
    if (!spring) {
        jointError = world.maxJointError();
    } else {
        energy -= world.jointReadout(*spring).elasticEnergy;
        const std::span<const Joint> joints = world.joints();
        for (std::size_t index = 0; index < joints.size(); ++index) {
            if (!joints[index].alive || index == spring->index) continue;
            const JointId id{static_cast<uint32_t>(index), joints[index].generation};
            jointError = std::max(jointError, world.jointReadout(id).error);
        }
    }
    energy_.push(static_cast<float>(energy));
    jointError_.push(static_cast<float>(jointError));
}

render::RenderScene ViewSession::draw(const render::Camera& camera) {
    render::RenderScene scene = drawing_->draw(instance_.world);
    scene.camera = camera;
    if (const std::optional<render::DebugLine> spring = dragger_.line(instance_.world)) scene.lines.push_back(*spring);
    return scene;
}

}  // namespace substep::view
