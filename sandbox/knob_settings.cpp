#include "knob_settings.h"

#include "command_options.h"

#include <charconv>
#include <cmath>

namespace substep {

namespace {

/// "a, b, c" of the script's knob names, or "none".
std::string knobList(const SceneScript* script) {
    if (script == nullptr || script->knobs().empty()) return "none";
    std::string list;
    for (const SceneKnob& knob : script->knobs()) {
        if (!list.empty()) list += ", ";
        list += knob.name;
    }
    return list;
}

}  // namespace

std::vector<KnobSetting> parseKnobSettings(const std::vector<std::string>& texts) {
    std::vector<KnobSetting> settings;
    for (const std::string& text : texts) {
        const std::size_t equals = text.find('=');
        if (equals == std::string::npos || equals == 0) {
            throw UsageError("--set: expected NAME=VALUE, got '" + text + "'");
        }
        const std::string valueText = text.substr(equals + 1);
        double value = 0.0;
        const char* end = valueText.data() + valueText.size();
        const auto [last, error] = std::from_chars(valueText.data(), end, value);
        if (valueText.empty() || error != std::errc() || last != end || !std::isfinite(value)) {
            throw UsageError("--set " + text + ": expected a finite number after '='");
        }
        settings.push_back({text.substr(0, equals), value});
    }
    return settings;
}

void applyKnobSettings(LiveScene& scene, const std::vector<KnobSetting>& settings, const std::string& label) {
    if (settings.empty()) return;
    const auto setAll = [&] {
        for (const KnobSetting& setting : settings) {
            if (!scene.setKnob(setting.name, setting.value)) {
                const SceneScript* script = scene.script();
                throw UsageError("--set " + setting.name + ": " + label + " has no such knob (its knobs: " +
                                 knobList(script) + ")");
            }
        }
    };
    // Knobs of the starting state (a release angle, a throw) act through the script's start(),
    // others (the solver split) when changed: set them, start afresh from them as the window's
    // restart does, and set them again.
    setAll();
    scene.restart();
    setAll();
}

}  // namespace substep
