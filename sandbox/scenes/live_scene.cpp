#include "scenes/live_scene.h"

#include <utility>

namespace substep {

LiveScene::LiveScene(SceneDescription description, const SceneEntry* entry)
    : description_(std::move(description)),
      script_(entry != nullptr && entry->makeScript != nullptr ? entry->makeScript() : nullptr),
      instance_(buildScene(description_)) {
    if (script_) script_->start(instance_);
    canSnapshot_ = !script_ || script_->clone() != nullptr;
    sync();
}

std::chrono::steady_clock::duration LiveScene::step() {
    if (frameOpen()) return finishFrame();
    if (script_) script_->beforeFrame(instance_, time(), description_.dt);
    const auto worldStep = instance_.physics().step(description_.dt);
    ++frame_;
    return worldStep;
}

bool LiveScene::stepSubstep() {
    ecs::PhysicsSystem physics = instance_.physics();
    if (!physics.frameOpen()) {
        if (script_) script_->beforeFrame(instance_, time(), description_.dt);
        physics.beginFrame(description_.dt);
    }
    return physics.substep();
}

std::chrono::steady_clock::duration LiveScene::finishFrame() {
    if (!frameOpen()) return {};
    const auto worldStep = instance_.physics().finishFrame();
    ++frame_;
    return worldStep;
}

void LiveScene::restart() {
    instance_ = buildScene(description_);
    frame_ = 0;
    if (script_) script_->start(instance_);
    sync();
}

void LiveScene::sync() {
    ecs::PhysicsSystem physics = instance_.physics();
    physics.sync();
    physics.writeBack();
}

bool LiveScene::setKnob(std::string_view name, double value) {
    if (!script_ || !script_->setKnob(instance_, name, value)) return false;
    sync();
    return true;
}

bool LiveScene::canSnapshot() const { return canSnapshot_; }

LiveSceneSnapshot LiveScene::snapshot() const {
    LiveSceneSnapshot s;
    s.world = instance_.world().snapshot();  // a read of the world: no change goes round the layer
    if (script_) s.script = script_->clone();
    s.frame = frame_;
    return s;
}

void LiveScene::restore(const LiveSceneSnapshot& snapshot) {
    instance_.physics().restore(snapshot.world);
    if (snapshot.script) script_ = snapshot.script->clone();
    frame_ = snapshot.frame;
}

}  // namespace substep
