#pragma once
/// `--set NAME=VALUE`: turns a built-in scene's knob (scene_script.h) from the command line, as
/// its panel does in the viewer, so a run, a render or a regression capture can show the same
/// scene with the velocity pass off, another solver split or another target.

#include "scenes/live_scene.h"

#include <string>
#include <vector>

namespace substep {

struct KnobSetting {
    std::string name;
    double value = 0.0;
};

/// Each "NAME=VALUE" of --set. Throws UsageError naming --set for text of another form or a
/// value that is not a finite number.
std::vector<KnobSetting> parseKnobSettings(const std::vector<std::string>& texts);

/// Sets every knob on `scene`'s script, in order (a Toggle takes 0 or 1, a Choice the index of
/// its option, a Slider is clamped to its range), then restarts the scene from them and sets
/// them again, so knobs of the initial state take effect as well as the others. Call it before
/// the first frame. Throws UsageError naming --set and `label`
/// when the scene has no script or no knob of that name, listing the knobs it has.
void applyKnobSettings(LiveScene& scene, const std::vector<KnobSetting>& settings, const std::string& label);

}  // namespace substep
