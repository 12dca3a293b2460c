#include "view/view_session.h"

#include "ecs/components.h"

#include <algorithm>
#include <chrono>

namespace substep::view {

namespace {

SessionControls controlsOf(const SceneDescription& description, const SessionControls& kept) {
    SessionControls controls = kept;
    controls.substeps = description.substeps;
    controls.iterations = description.iterations;
    controls.jointProjection = description.jointProjection;
    controls.sweptRestitution = description.sweptRestitution;
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
    selected_.reset();
    selectedJoint_.reset();
    // A new world records nothing until substeps are stepped again.
    recordingCorrections_ = false;
    corrections_.clear();
    velocityChanges_.clear();
    softCorrections_.clear();
    correctionsSubstep_ = correctionsSubsteps_ = 0;
    // A restart keeps the script, and with it the knobs the user turned.
    if (keepScript && live_) {
        live_->restart();
    } else {
        live_ = std::make_unique<LiveScene>(startLabelledScene(source_));
    }
    applyControls();
    makeDrawing();
    chainMeasure_.reset();
    if (source_.entry != nullptr && !source_.entry->chain.endBody.empty()) {
        chainMeasure_ = std::make_unique<ErrorRecorder>(live_->instance(),
                                                        errorReference(source_.entry, live_->instance()));
    }
    namedJoints_.clear();
    const SceneInstance& scene = live_->instance();
    for (const ecs::Entity joint : scene.jointEntities)
        if (const ecs::Name* name = scene.registry.tryGet<ecs::Name>(joint)) namedJoints_.emplace_back(name->value, joint);
    finite_ = live_->world().isFinite();
    lastStepMs_ = 0.0;
    energy_.clear();
    jointError_.clear();
    chainElongation_.clear();
    columnPlots_.reset(live_->instance());
    sample();
    restartHistory();
}

void ViewSession::restartHistory() {
    timeline_.clear();
    if (live_->canSnapshot()) timeline_.record(live_->snapshot(), live_->description().dt);
}

bool ViewSession::scrubTo(long long frame) {
    // A frame left open by substep stepping goes back to its start even at the same frame.
    const bool open = live_->frameOpen();
    if (dragger_.active() || timeline_.empty() || (frame == live_->frame() && !open)) return false;
    const LiveSceneSnapshot* snapshot = timeline_.seek(frame);
    if (snapshot == nullptr || (snapshot->frame == live_->frame() && !open)) return false;
    live_->restore(*snapshot);
    finite_ = live_->world().isFinite();
    columnPlots_.showUpTo(live_->frame());
    readCorrections();
    return true;
}

bool ViewSession::grab(const Ray& ray) {
    const bool grabbed = dragger_.grab(live_->physics(), ray);
    live_->sync();
    if (grabbed) restartHistory();  // the drag spring is an entity the kept states lack
    return grabbed;
}

void ViewSession::drag(const Ray& ray) {
    dragger_.drag(live_->instance().registry, ray);
    live_->sync();
}

void ViewSession::release() {
    const bool held = dragger_.active();
    dragger_.release(live_->physics());
    live_->sync();
    if (held) restartHistory();
}

bool ViewSession::select(const Ray& ray, double radiansPerPixel) {
    if (radiansPerPixel > 0.0) {
        if (const std::optional<ecs::Entity> joint = pickJoint(live_->instance(), ray, radiansPerPixel)) {
            selectJoint(*joint);
            return true;
        }
    }
    const std::optional<BodyHit> hit = pickBody(live_->instance().registry, ray);
    selected_ = hit ? std::optional(hit->entity) : std::nullopt;
    selectedJoint_.reset();
    return selected_.has_value();
}

void ViewSession::selectJoint(ecs::Entity joint) {
    selectedJoint_ = joint;
    selected_.reset();
}

std::optional<JointDetails> ViewSession::jointInspection() {
    if (!selectedJoint_) return std::nullopt;
    return inspectJoint(live_->instance(), *selectedJoint_);
}

std::optional<BodyInspection> ViewSession::inspection() {
    if (!selected_) return std::nullopt;
    std::optional<BodyInspection> inspection = inspectBody(live_->instance().registry, *selected_);
    const ecs::RigidBody* rigid = live_->instance().registry.tryGet<ecs::RigidBody>(*selected_);
    if (!inspection || rigid == nullptr || !live_->world().isValid(rigid->id)) return inspection;
    const World& world = live_->world();
    inspection->inertia = world.bodies()[rigid->id.index].inertia;
    for (const ContactPair& pair : world.contactPairs())
        if (pair.body0 == rigid->id.index || pair.body1 == rigid->id.index) inspection->contacts += static_cast<int>(pair.count);
    return inspection;
}

double ViewSession::jointCompliance(ecs::Entity joint) const {
    const ecs::Joint* component = live_->instance().registry.tryGet<ecs::Joint>(joint);
    return component != nullptr ? component->def.compliance : 0.0;
}

void ViewSession::setJointCompliance(ecs::Entity joint, double compliance) {
    ecs::Registry& registry = live_->instance().registry;
    if (!registry.has<ecs::Joint>(joint) || !(compliance >= 0.0)) return;
    registry.patch<ecs::Joint>(joint, [&](ecs::Joint& component) { component.def.compliance = compliance; });
    live_->sync();
    restartHistory();
}

void ViewSession::setKnob(std::size_t index, double value) {
    SceneScript* script = live_->script();
    if (script == nullptr || index >= script->knobs().size()) return;
    live_->setKnob(script->knobs()[index].name, value);
    restartHistory();
    // A knob may switch the solver (the bunny chain's 20 x 1 against 1 x 20): the panel's
    // sliders follow, so a restart keeps what the knob chose.
    controls_.substeps = live_->world().settings().substeps;
    controls_.iterations = live_->world().settings().iterations;
}

void ViewSession::applyControls() {
    ecs::PhysicsSystem physics = live_->physics();
    WorldSettings settings = physics.settings();
    settings.substeps = controls_.substeps;
    settings.iterations = controls_.iterations;
    settings.jointProjection = controls_.jointProjection;
    settings.sweptRestitution = controls_.sweptRestitution;
    settings.gravity.y() = controls_.gravityY;
    settings.measureTime = true;  // the panel's stage breakdown
    physics.setSettings(settings);
}

void ViewSession::applyDrawingOptions() { drawing_->setOptions(controls_.drawing); }

void ViewSession::makeDrawing() {
    // SceneDrawing fixes its camera, ground and force scale from the state it is made from; a
    // fresh build of the scene gives the same ones as at the start, whatever the world did since.
    SceneInstance initial = buildLabelledScene(source_.description, source_.label);
    drawing_ = std::make_unique<SceneDrawing>(source_.description, initial, aspect_, controls_.drawing);
}

void ViewSession::stepOnce() {
    if (!finite_) return;
    const auto start = std::chrono::steady_clock::now();
    live_->step();
    lastStepMs_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    frameEnded();
}

void ViewSession::stepSubstep() {
    if (!finite_) return;
    if (!recordingCorrections_) {
        live_->physics().recordCorrections(true);
        recordingCorrections_ = true;
    }
    live_->stepSubstep();
    finite_ = live_->world().isFinite();
    readCorrections();
    // The frame's last substep ends it: the frame counts, and the timeline keeps it, as if it
    // had been stepped whole (the bytes are the same).
    if (live_->frameOpen() && live_->frameSubstepsDone() >= live_->frameSubsteps()) {
        live_->finishFrame();
        frameEnded();
    }
}

void ViewSession::stopRecordingCorrections() {
    if (!recordingCorrections_) return;
    live_->physics().recordCorrections(false);
    recordingCorrections_ = false;
    readCorrections();
}

void ViewSession::readCorrections() {
    corrections_ = recordingCorrections_ ? listCorrections(live_->instance()) : std::vector<CorrectionEntry>{};
    velocityChanges_ = recordingCorrections_ ? listVelocityChanges(live_->instance()) : std::vector<VelocityEntry>{};
    softCorrections_ = recordingCorrections_ ? listSoftCorrections(live_->instance()) : std::vector<SoftStageEntry>{};
    const SubstepCorrections* record = live_->world().corrections();
    correctionsSubstep_ = record != nullptr ? record->substep() : 0;
    correctionsSubsteps_ = record != nullptr ? record->frameSubsteps() : 0;
}

void ViewSession::frameEnded() {
    finite_ = live_->world().isFinite();
    if (finite_) sample();
    if (recordingCorrections_) readCorrections();
    // Recorded after the step; a step from a scrubbed-back frame drops the later history.
    if (finite_ && live_->canSnapshot()) timeline_.record(live_->snapshot(), live_->description().dt);
}

void ViewSession::sample() {
    // The plots measure the scene, not the hand pulling it: the drag spring's stretch and stored
    // energy are left out (the work it does still shows as a change of the scene's energy).
    const World& world = live_->world();
    const ecs::Registry& registry = live_->instance().registry;
    const std::optional<ecs::Entity> spring = dragger_.joint();
    double energy = world.energies().total();
    double jointError = 0.0;
    if (!spring) {
        jointError = world.maxJointError();
    } else {
        if (const ecs::Joint* held = registry.tryGet<ecs::Joint>(*spring)) energy -= held->readout.elasticEnergy;
        for (const ecs::Entity joint : live_->instance().jointEntities)
            if (const ecs::Joint* component = registry.tryGet<ecs::Joint>(joint))
                jointError = std::max(jointError, component->readout.error);
    }
    energy_.push(static_cast<float>(energy));
    jointError_.push(static_cast<float>(jointError));
    if (chainMeasure_) {
        chainMeasure_->sample();
        chainElongation_.push(static_cast<float>(chainMeasure_->measures().chainElongation.value_or(0.0)));
    }
    columnPlots_.record(live_->instance(), live_->frame(), live_->time());
}

render::RenderScene ViewSession::draw(const render::Camera& camera) {
    render::RenderScene scene = drawing_->draw(live_->instance());
    scene.camera = camera;
    // A script may ask for a camera of its own (one following a body): it wins while it asks.
    if (const SceneScript* script = live_->script())
        if (const std::optional<SceneCamera> own = script->camera(live_->instance())) scene.camera = renderCamera(*own);
    if (const std::optional<render::DebugLine> spring = dragger_.line(live_->instance().registry))
        scene.lines.push_back(*spring);
    if (selected_) outlineBody(live_->instance().registry, *selected_, render::Colour(1.0f, 0.85f, 0.1f), scene.lines);
    // A selected joint is marked in the selection's yellow too.
    if (selectedJoint_) highlightJoint(live_->instance(), *selectedJoint_, render::Colour(1.0f, 0.85f, 0.1f), scene.lines);
    drawCorrections(corrections_, live_->world(), scene.lines);
    drawVelocityChanges(velocityChanges_, live_->world(), scene.lines);
    drawSoftCorrections(softCorrections_, live_->world(), scene.lines);
    return scene;
}

}  // namespace substep::view
