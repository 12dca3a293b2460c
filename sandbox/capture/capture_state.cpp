#include "capture/capture_state.h"

#include "capture/json_input.h"
#include "error_measures.h"
#include "knob_settings.h"
#include "scene_drawing.h"
#include "scene_source.h"

#include <optional>

namespace substep::capture {

struct CaptureScene::Impl {
    SceneSource source;
    std::optional<LiveScene> live;
    std::optional<ErrorRecorder> recorder;
    std::optional<SceneDrawing> drawing;
    std::vector<std::string> bodyNames;   ///< by world body index
    std::vector<std::string> jointNames;  ///< by world joint index
};

namespace {

/// "a, b, c" of the script's knob names, or "none".
std::string knobNames(const SceneScript* script) {
    if (script == nullptr || script->knobs().empty()) return "none";
    std::string list;
    for (const SceneKnob& knob : script->knobs())
        list += (list.empty() ? "" : ", ") + knob.name;
    return list;
}

bool hasKnob(const SceneScript* script, const std::string& name) {
    if (script == nullptr) return false;
    for (const SceneKnob& knob : script->knobs())
        if (knob.name == name) return true;
    return false;
}

}  // namespace

CaptureScene::CaptureScene(const CaptureSpec& spec, const std::string& scriptFile)
    : impl_(std::make_unique<Impl>()) {
    Impl& impl = *impl_;
    impl.source = resolveScene(spec.scenePath);
    SceneDescription description = impl.source.description;
    if (spec.dt) description.dt = *spec.dt;
    if (spec.substeps) description.substeps = *spec.substeps;
    if (spec.iterations) description.iterations = *spec.iterations;
    if (spec.image && spec.image->camera) description.camera = spec.image->camera;
    impl.live.emplace(startLabelledScene(impl.source, description));
    LiveScene& live = *impl.live;

    // Knobs as `run --set` turns them; checked here first so the message names the script's path.
    std::vector<KnobSetting> knobs;
    for (const auto& [name, value] : spec.knobs) {
        if (!hasKnob(live.script(), name)) {
            throw InputError(
                scriptFile, spec.path + ".set." + name,
                spec.scene + " has no such knob (its knobs: " + knobNames(live.script()) + ")");
        }
        knobs.push_back({name, value});
    }
    applyKnobSettings(live, knobs, impl.source.label);
    // substeps and iterations win over a knob that switches the solver, as in `run`.
    WorldSettings solver = live.world().settings();
    if (spec.substeps) solver.substeps = *spec.substeps;
    if (spec.iterations) solver.iterations = *spec.iterations;
    live.world().setSettings(solver);

    const SceneInstance& instance = live.instance();
    impl.bodyNames.resize(live.world().bodies().size());
    for (const auto& [name, id] : instance.namedBodies)
        impl.bodyNames[id.index] = name;
    impl.jointNames.resize(live.world().joints().size());
    for (const auto& [name, id] : instance.namedJoints)
        impl.jointNames[id.index] = name;
    if (spec.metrics.any())
        impl.recorder.emplace(instance, errorReference(impl.source.entry, live.world()));
    if (spec.image) {
        impl.drawing.emplace(
            live.description(), live.world(),
            static_cast<float>(spec.image->width) / static_cast<float>(spec.image->height));
    }
}

CaptureScene::~CaptureScene() = default;
CaptureScene::CaptureScene(CaptureScene&&) noexcept = default;
CaptureScene& CaptureScene::operator=(CaptureScene&&) noexcept = default;

void CaptureScene::step() {
    impl_->live->step();
}

long long CaptureScene::frame() const {
    return impl_->live->frame();
}

bool CaptureScene::isFinite() const {
    return impl_->live->world().isFinite();
}

void CaptureScene::readState(CaptureState& state) const {
    const LiveScene& live = *impl_->live;
    const World& world = live.world();
    state.frame = live.frame();
    state.time = live.time();

    // Body 0 is the world's own anchor, not a scene body.
    std::size_t count = 0;
    const std::span<const Body> bodies = world.bodies();
    for (std::size_t index = 1; index < bodies.size(); ++index) {
        const Body& body = bodies[index];
        if (!body.alive) continue;
        if (state.bodies.size() <= count) state.bodies.emplace_back();
        BodyState& out = state.bodies[count++];
        out.name = index < impl_->bodyNames.size() ? impl_->bodyNames[index] : std::string();
        const Vec3 position = body.userPosition();
        const Quat orientation = body.userOrientation();
        out.position = {position.x(), position.y(), position.z()};
        out.orientation = {orientation.w(), orientation.x(), orientation.y(), orientation.z()};
        out.velocity = {body.v.x(), body.v.y(), body.v.z()};
        out.angularVelocity = {body.omega.x(), body.omega.y(), body.omega.z()};
    }
    state.bodies.resize(count);

    count = 0;
    const std::span<const Joint> joints = world.joints();
    for (std::size_t index = 0; index < joints.size(); ++index) {
        const Joint& joint = joints[index];
        if (!joint.alive) continue;
        if (state.joints.size() <= count) state.joints.emplace_back();
        JointState& out = state.joints[count++];
        out.name = index < impl_->jointNames.size() ? impl_->jointNames[index] : std::string();
        const JointReadout readout =
            world.jointReadout(JointId{static_cast<uint32_t>(index), joint.generation});
        out.force = readout.force;
        out.torque = readout.torque;
        out.error = readout.error;
    }
    state.joints.resize(count);

    // This build's World has no soft bodies yet; when it gains them, their centres and volumes
    // are read here and everything downstream (files, comparison, digest) already carries them.
    state.softBodies.clear();
}

void CaptureScene::sampleMetrics() {
    if (impl_->recorder) impl_->recorder->sample();
}

RunMetrics CaptureScene::metrics() const {
    if (!impl_->recorder) return {};
    const ErrorMeasures measures = impl_->recorder->measures();
    return {.maxJointError = measures.maxJointError,
            .energyDrift = measures.energyDrift,
            .penetration = measures.penetration};
}

render::RenderScene CaptureScene::draw() {
    return impl_->drawing->draw(impl_->live->instance());
}

}  // namespace substep::capture
