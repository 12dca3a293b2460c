#include "view/view_session.h"

#include <algorithm>
#include <chrono>

namespace substep::view {

namespace {

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
    rebuild(false);
}

void ViewSession::load(SceneSource source) {
    source_ = std::move(source);
    controls_ = controlsOf(source_.description, controls_);
    rebuild(false);
}

void ViewSession::restart() { rebuild(true); }

void ViewSession::rebuild(bool keepScript) {
    dragger_.forget();  // its spring goes with the old world
    // A restart keeps the script, and with it the knobs the user turned.
    if (keepScript && live_) {
        live_->restart();
    } else {
        live_ = std::make_unique<LiveScene>(startLabelledScene(source_));
    }
    applyControls();
    applyDrawingOptions();
    chainMeasure_.reset();
    if (source_.entry != nullptr && !source_.entry->chain.endBody.empty()) {
        chainMeasure_ = std::make_unique<ErrorRecorder>(live_->instance(),
                                                        errorReference(source_.entry, live_->world()));
    }
    finite_ = live_->world().isFinite();
    lastStepMs_ = 0.0;
    energy_.clear();
    jointError_.clear();
    chainElongation_.clear();
    sample();
}

void ViewSession::setJointCompliance(JointId id, double compliance) {
    World& world = live_->world();
    if (world.isValid(id) && compliance >= 0.0) world.joint(id).compliance = compliance;
}

void ViewSession::setKnob(std::size_t index, double value) {
    SceneScript* script = live_->script();
    if (script == nullptr || index >= script->knobs().size()) return;
    script->setKnob(live_->instance(), script->knobs()[index].name, value);
    // A knob may switch the solver (the bunny chain's 20 x 1 against 1 x 20): the panel's
    // sliders follow, so a restart keeps what the knob chose.
    controls_.substeps = live_->world().settings().substeps;
    controls_.iterations = live_->world().settings().iterations;
}

void ViewSession::applyControls() {
    WorldSettings settings = live_->world().settings();
    settings.substeps = controls_.substeps;
    settings.iterations = controls_.iterations;
    settings.gravity.y() = controls_.gravityY;
    settings.measureTime = true;  // the panel's stage breakdown
    live_->world().setSettings(settings);
}

void ViewSession::applyDrawingOptions() {
    // SceneDrawing fixes its camera, ground and force scale from the state it is made from; a
    // fresh build of the scene gives the same ones as at the start, whatever the world did since.
    const SceneInstance initial = buildLabelledScene(source_.description, source_.label);
    drawing_ = std::make_unique<SceneDrawing>(source_.description, initial.world, aspect_, controls_.drawing);
}

void ViewSession::stepOnce() {
    if (!finite_) return;
    const auto start = std::chrono::steady_clock::now();
    live_->step();
    lastStepMs_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    finite_ = live_->world().isFinite();
    if (finite_) sample();
}

void ViewSession::sample() {
    // The plots measure the scene, not the hand pulling it: the drag spring's stretch and stored
    // energy are left out (the work it does still shows as a change of the scene's energy).
    const World& world = live_->world();
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
    if (chainMeasure_) {
        chainMeasure_->sample();
        chainElongation_.push(static_cast<float>(chainMeasure_->measures().chainElongation.value_or(0.0)));
    }
}

render::RenderScene ViewSession::draw(const render::Camera& camera) {
    render::RenderScene scene = drawing_->draw(live_->instance());
    scene.camera = camera;
    // A script may ask for a camera of its own (one following a body): it wins while it asks.
    if (const SceneScript* script = live_->script())
        if (const std::optional<SceneCamera> own = script->camera(live_->instance())) scene.camera = renderCamera(*own);
    if (const std::optional<render::DebugLine> spring = dragger_.line(live_->world())) scene.lines.push_back(*spring);
    return scene;
}

}  // namespace substep::view
