#include "scenes/scene_script.h"

#include <algorithm>
#include <cmath>

namespace substep {

SceneKnob* SceneScript::findKnob(std::string_view name) {
    for (SceneKnob& knob : knobs_)
        if (knob.name == name) return &knob;
    return nullptr;
}

bool SceneScript::setKnob(SceneInstance& scene, std::string_view name, double value) {
    SceneKnob* knob = findKnob(name);
    if (knob == nullptr || !std::isfinite(value)) return false;
    switch (knob->kind) {
        case SceneKnob::Kind::Toggle: value = value != 0.0 ? 1.0 : 0.0; break;
        case SceneKnob::Kind::Slider: value = std::clamp(value, knob->min, knob->max); break;
        case SceneKnob::Kind::Choice:
            if (knob->choices.empty()) return false;
            value = std::clamp(std::round(value), 0.0, static_cast<double>(knob->choices.size()) - 1.0);
            break;
    }
    knob->value = value;
    knobChanged(scene, static_cast<std::size_t>(knob - knobs_.data()));
    return true;
}

std::size_t SceneScript::addKnob(SceneKnob knob) {
    knobs_.push_back(std::move(knob));
    return knobs_.size() - 1;
}

}  // namespace substep
