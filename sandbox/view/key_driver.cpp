// The keyboard and gamepad side of SceneKeyAxis: keys are read through ImGui (the GLFW backend
// feeds it), the gamepad through GLFW's mapped gamepad state.

#include "view/key_driver.h"

#include <GLFW/glfw3.h>
#include <imgui.h>

#include <cctype>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

namespace substep::view {
namespace {

constexpr double kStickDeadZone = 0.15;

/// GLFW key code of a key name ("W", "Up", ...), or GLFW_KEY_UNKNOWN.
int keyCode(const std::string& name) {
    if (name == "Up") return GLFW_KEY_UP;
    if (name == "Down") return GLFW_KEY_DOWN;
    if (name == "Left") return GLFW_KEY_LEFT;
    if (name == "Right") return GLFW_KEY_RIGHT;
    if (name.size() == 1 && std::isalpha(static_cast<unsigned char>(name[0])))
        return GLFW_KEY_A + (std::toupper(static_cast<unsigned char>(name[0])) - 'A');
    return GLFW_KEY_UNKNOWN;
}

bool anyHeld(const std::string& keys) {
    std::istringstream names(keys);
    std::string name;
    while (names >> name) {
        const int code = keyCode(name);
        if (code != GLFW_KEY_UNKNOWN && ImGui::IsKeyDown(static_cast<ImGuiKey>(code))) return true;
    }
    return false;
}

}  // namespace

std::vector<int> KeyDriver::boundKeys(CompareSession& session) const {
    std::vector<int> keys;
    const SceneScript* script = session.first().script();
    if (script == nullptr) return keys;
    for (const SceneKeyAxis& axis : script->keyAxes())
        for (const std::string* names : {&axis.positiveKeys, &axis.negativeKeys}) {
            std::istringstream words(*names);
            std::string name;
            while (words >> name)
                if (const int code = keyCode(name); code != GLFW_KEY_UNKNOWN) keys.push_back(code);
        }
    return keys;
}

void KeyDriver::update(CompareSession& session) {
    SceneScript* script = session.first().script();
    if (script == nullptr) {
        applied_.clear();
        return;
    }
    // Paused, the keys are the window's: nothing is driven, nothing let go (a knob put back to
    // rest now would start a new history at the paused frame).
    if (!session.playback().playing) return;
    const std::span<const SceneKeyAxis> axes = script->keyAxes();
    applied_.resize(axes.size(), std::numeric_limits<double>::quiet_NaN());
    const bool keyboard = !ImGui::GetIO().WantCaptureKeyboard;
    GLFWgamepadstate pad{};
    const bool gamepad = glfwJoystickIsGamepad(GLFW_JOYSTICK_1) && glfwGetGamepadState(GLFW_JOYSTICK_1, &pad);
    for (std::size_t i = 0; i < axes.size(); ++i) {
        const SceneKeyAxis& axis = axes[i];
        const int direction = keyboard ? static_cast<int>(anyHeld(axis.positiveKeys)) -
                                             static_cast<int>(anyHeld(axis.negativeKeys))
                                       : 0;
        double stick = 0.0;
        if (gamepad && axis.gamepadAxis >= 0 && axis.gamepadAxis <= GLFW_GAMEPAD_AXIS_LAST)
            stick = pad.axes[axis.gamepadAxis] * (axis.invertGamepad ? -1.0 : 1.0);
        const bool sticking = std::abs(stick) > kStickDeadZone;
        const bool driving = direction != 0 || sticking;
        const bool wasDriving = !std::isnan(applied_[i]);
        if (!driving && !wasDriving) continue;  // the panel's slider is the user's
        const double value = direction != 0 ? axis.rest + direction * axis.amount
                             : sticking     ? axis.rest + stick * axis.amount
                                            : axis.rest;
        if (value != applied_[i]) {
            const SceneKnob* knob = script->findKnob(axis.knob);
            if (knob != nullptr) session.setKnob(static_cast<std::size_t>(knob - script->knobs().data()), value);
        }
        applied_[i] = driving ? value : std::numeric_limits<double>::quiet_NaN();
    }
}

}  // namespace substep::view
