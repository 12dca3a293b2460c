#pragma once
/// A scene as it runs: its built instance, its script (scene_script.h) and the frame count.
/// Every command and the viewer step scenes through this, so a script acts the same in each.

#include "scenes/scene_registry.h"
#include "scenes/scene_script.h"

#include "scene/scene.h"

#include <memory>

namespace substep {

class LiveScene {
  public:
    /// Builds `description` (throws what buildScene throws) and, when `entry` has one, makes
    /// its script and starts it. `entry` is the built-in scene the description came from, or
    /// nullptr for a scene file.
    LiveScene(SceneDescription description, const SceneEntry* entry);

    /// One frame of the scene's dt: the script's beforeFrame, then the world's step.
    void step();
    /// Builds the scene again from its description; the script keeps its knobs.
    void restart();

    SceneInstance& instance() { return instance_; }
    const SceneInstance& instance() const { return instance_; }
    World& world() { return instance_.world; }
    const World& world() const { return instance_.world; }
    /// The script, or nullptr.
    SceneScript* script() { return script_.get(); }
    const SceneScript* script() const { return script_.get(); }
    const SceneDescription& description() const { return description_; }

    long long frame() const { return frame_; }
    /// Simulated time: frame x dt, not a running sum.
    double time() const { return static_cast<double>(frame_) * description_.dt; }

  private:
    SceneDescription description_;
    std::unique_ptr<SceneScript> script_;
    SceneInstance instance_;
    long long frame_ = 0;
};

}  // namespace substep
