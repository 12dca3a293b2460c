#include "scenes/live_scene.h"

#include <utility>

namespace substep {

LiveScene::LiveScene(SceneDescription description, const SceneEntry* entry)
    : description_(std::move(description)),
      script_(entry != nullptr && entry->makeScript != nullptr ? entry->makeScript() : nullptr),
      instance_(buildScene(description_)) {
    if (script_) script_->start(instance_);
}

void LiveScene::step() {
    if (script_) script_->beforeFrame(instance_, time(), description_.dt);
    instance_.world.step(description_.dt);
    ++frame_;
}

void LiveScene::restart() {
    instance_ = buildScene(description_);
    frame_ = 0;
    if (script_) script_->start(instance_);
}

}  // namespace substep
