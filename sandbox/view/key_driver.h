#pragma once
/// Drives the knobs a scene's script binds to keys (SceneKeyAxis, scenes/scene_script.h) from
/// the keyboard and the first gamepad GLFW sees: the RC car's throttle and steering.

#include "view/compare_session.h"

#include <vector>

namespace substep::view {

class KeyDriver {
  public:
    /// Once per frame, after ImGui's new frame: sets each bound knob of the session's scene whose
    /// keys or stick are in use (both runs in compare mode), and puts it back to its rest value
    /// once they are let go. Keys are ignored while a text box has the keyboard. Only while the
    /// run plays: paused, the bound keys are the window's (S steps, Left/Right scrub,
    /// Shift+Right steps a substep; view_controls.h) and the knobs stay as they were, so a
    /// paused frame, its substeps and the timeline are not changed by a key meant for them.
    void update(CompareSession& session);
    /// Every GLFW key the current scene binds (keyActions' drivenKeys).
    std::vector<int> boundKeys(CompareSession& session) const;

  private:
    std::vector<double> applied_;  ///< per axis: the value last set while driving; NaN when idle
};

}  // namespace substep::view
