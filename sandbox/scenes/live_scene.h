#pragma once
/// A scene as it runs: its built instance, its script (scene_script.h) and the frame count.
/// Every command and the viewer step scenes through this, so a script acts the same in each;
/// and this steps the scene through the engine layer's physics system, the only way the
/// sandbox reaches the world.

#include "scenes/scene_registry.h"
#include "scenes/scene_script.h"

#include "scene/scene.h"

#include "physics/world_snapshot.h"

#include <chrono>
#include <memory>
#include <string_view>

namespace substep {

/// A running scene's state at a frame boundary (LiveScene::snapshot): the world's, a copy of the
/// script, the frame count. Restoring it makes the following frames repeat the original ones
/// byte for byte.
struct LiveSceneSnapshot {
    WorldSnapshot world;
    std::shared_ptr<const SceneScript> script;  ///< null for a scene without a script
    long long frame = 0;
};

class LiveScene {
  public:
    /// Builds `description` (throws what buildScene throws) and, when `entry` has one, makes
    /// its script and starts it. `entry` is the built-in scene the description came from, or
    /// nullptr for a scene file.
    LiveScene(SceneDescription description, const SceneEntry* entry);

    /// One frame of the scene's dt: the script's beforeFrame, then the physics system's step
    /// (patched components applied, the world stepped, its state written back into components).
    /// Returns the time of the world's step alone, which the commands report.
    std::chrono::steady_clock::duration step();
    /// The same frame a substep at a time (the viewer's substep stepping): the first call begins
    /// the frame (the script's beforeFrame, the physics system's beginFrame) and solves its first
    /// substep; each later call the next one. False when the frame has no substep left. A frame
    /// left open is finished by finishFrame() or step(); either way its bytes are step()'s.
    bool stepSubstep();
    /// Solves the open frame's remaining substeps and ends it (counted as a frame); nothing when
    /// none is open. Returns the time of the world's work it did.
    std::chrono::steady_clock::duration finishFrame();
    /// Whether a frame is open, and its substeps done and in all (0 while none is open).
    bool frameOpen() const { return instance_.world().frameOpen(); }
    int frameSubstepsDone() const { return frameOpen() ? instance_.world().frameSubstepsDone() : 0; }
    int frameSubsteps() const { return frameOpen() ? instance_.world().frameSubsteps() : 0; }
    /// Builds the scene again from its description; the script keeps its knobs.
    void restart();
    /// Applies what the script or the caller changed in components (Registry::patch) to the
    /// world now, and reads the world back into components, rather than at the next step: for
    /// outputs of the state before the first step, and for a knob turned while paused.
    void sync();
    /// Sets knob `name` of the script and syncs; false when there is no script or no such knob.
    bool setKnob(std::string_view name, double value);

    /// Whether snapshot() captures everything: the scene has no script or its script can be
    /// copied (SceneScript::clone).
    bool canSnapshot() const;
    /// The state now (at a frame boundary: an open frame is not captured mid-way; finish it
    /// first); with a script that cannot be copied the snapshot keeps none (see
    /// canSnapshot) and a restore keeps the current script.
    LiveSceneSnapshot snapshot() const;
    /// Puts the scene back in `snapshot`'s state: the world (components written back from it),
    /// the script and the frame count. The snapshot must come from this build of the scene (no
    /// restart or load since); the world's settings stay the current ones.
    void restore(const LiveSceneSnapshot& snapshot);

    SceneInstance& instance() { return instance_; }
    const SceneInstance& instance() const { return instance_; }
    /// The scene's physics system (made per call).
    ecs::PhysicsSystem physics() { return instance_.physics(); }
    /// The world, read-only (global measures: energies, penetration, step times).
    const World& world() const { return instance_.world(); }
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
    bool canSnapshot_ = true;  ///< no script, or one that copies
};

}  // namespace substep
