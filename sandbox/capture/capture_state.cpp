#include "capture/capture_state.h"

#include "ecs/components.h"
#include "ecs/physics_system.h"
#include "ecs/soft_body_component.h"

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
    ecs::PhysicsSystem physics = live.physics();
    WorldSettings solver = physics.settings();
    if (spec.substeps) solver.substeps = *spec.substeps;
    if (spec.iterations) solver.iterations = *spec.iterations;
    physics.setSettings(solver);

    SceneInstance& instance = live.instance();
    if (spec.metrics.any())
        impl.recorder.emplace(instance, errorReference(impl.source.entry, instance));
    if (spec.image) {
        impl.drawing.emplace(
            live.description(), instance,
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
    const SceneInstance& scene = live.instance();
    const ecs::Registry& registry = scene.registry;
    state.frame = live.frame();
    state.time = live.time();

    // Every body and joint of the scene, named or not, in description order (the world's), read
    // from the components the physics system wrote after the last step.
    const auto nameOf = [&](ecs::Entity entity) {
        const ecs::Name* name = registry.tryGet<ecs::Name>(entity);
        return name != nullptr ? name->value : std::string();
    };
    std::size_t count = 0;
    for (const ecs::Entity entity : scene.bodyEntities) {
        const ecs::RigidBody* body = registry.tryGet<ecs::RigidBody>(entity);
        const ecs::Transform* transform = registry.tryGet<ecs::Transform>(entity);
        if (body == nullptr || transform == nullptr || body->id.isNull()) continue;
        if (state.bodies.size() <= count) state.bodies.emplace_back();
        BodyState& out = state.bodies[count++];
        out.name = nameOf(entity);
        const Vec3& position = transform->position;
        const Quat& orientation = transform->rotation;
        out.position = {position.x(), position.y(), position.z()};
        out.orientation = {orientation.w(), orientation.x(), orientation.y(), orientation.z()};
        out.velocity = {body->velocity.x(), body->velocity.y(), body->velocity.z()};
        out.angularVelocity = {body->angularVelocity.x(), body->angularVelocity.y(), body->angularVelocity.z()};
    }
    state.bodies.resize(count);

    count = 0;
    for (const ecs::Entity entity : scene.jointEntities) {
        const ecs::Joint* joint = registry.tryGet<ecs::Joint>(entity);
        if (joint == nullptr || joint->id.isNull()) continue;
        if (state.joints.size() <= count) state.joints.emplace_back();
        JointState& out = state.joints[count++];
        out.name = nameOf(entity);
        out.force = joint->readout.force;
        out.torque = joint->readout.torque;
        out.error = joint->readout.error;
    }
    state.joints.resize(count);

    // Soft bodies: centre of mass and volume (the volume on demand, ecs::softBodyReadout).
    count = 0;
    for (const ecs::Entity entity : scene.softBodyEntities) {
        const ecs::SoftBody* softBody = registry.tryGet<ecs::SoftBody>(entity);
        if (softBody == nullptr || softBody->id.isNull()) continue;
        if (state.softBodies.size() <= count) state.softBodies.emplace_back();
        SoftBodyState& out = state.softBodies[count++];
        out.name = nameOf(entity);
        const SoftBodyReadout readout = ecs::softBodyReadout(scene.world(), *softBody);
        const Vec3& centre = readout.centreOfMass;
        out.centre = {centre.x(), centre.y(), centre.z()};
        out.volume = readout.volume;
    }
    state.softBodies.resize(count);
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
