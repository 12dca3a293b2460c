#include "view/view_controls.h"

#include <GLFW/glfw3.h>

#include <algorithm>
#include <array>
#include <cstdio>

namespace substep::view {

namespace {

constexpr std::array<ControlHelp, 20> kControls{{
    {"Space", "play / pause"},
    {"S", "step one frame (hold to repeat); mid-frame, finish the frame"},
    {". or Shift+Right", "pause; one substep, what each constraint corrected drawn and listed"},
    {"Left / Right", "pause; one frame back / forward through the timeline (last 10 s; hold to repeat)"},
    {"R", "restart the scene (and reset the camera)"},
    {"C, Home", "reset the camera to the scene's"},
    {"Tab", "hide / show the panel"},
    {"F1", "this help"},
    {"P", "screenshot of the window as shown (PNG in the working folder)"},
    {"Shift+P", "screenshot of the 3D view without the panel"},
    {"B", "show / hide the bodies' broadphase boxes"},
    {"M", "show / hide the centres of mass"},
    {"V", "show / hide the velocities (v and omega; the panel's arrow scale sizes them)"},
    {"left drag", "orbit the camera"},
    {"Ctrl + left drag", "grab a body with a spring (paper Fig. 5) or move a mount"},
    {"left click", "select a body, or near a joint's anchor the joint, for the inspector"},
    {"right / middle drag", "pan"},
    {"wheel", "zoom"},
    {"panel: quality", "light / medium / full rendering (light on software GL)"},
    {"scene's keys", "rc_car: WASD / arrows drive while playing; paused, S, arrows, Shift+Right are the above"},
}};

}  // namespace

std::span<const ControlHelp> viewControls() { return kControls; }

std::string controlsHelpText() {
    std::string text = "Controls in the window:\n";
    for (const ControlHelp& control : kControls) {
        char line[256];
        std::snprintf(line, sizeof line, "  %-20s %s\n", control.keys, control.does);
        text += line;
    }
    return text;
}

KeyActions keyActions(std::span<const InputEvent> events, bool textInput, bool playing,
                      std::span<const int> drivenKeys) {
    KeyActions actions;
    for (const InputEvent& event : events) {
        if (event.kind != InputEvent::Kind::Key || event.action == GLFW_RELEASE) continue;
        const bool repeat = event.action == GLFW_REPEAT;
        // A key the scene drives with belongs to the driving while the run plays.
        if (playing && std::find(drivenKeys.begin(), drivenKeys.end(), event.code) != drivenKeys.end()) continue;
        switch (event.code) {
            case GLFW_KEY_F1:
                if (!repeat) ++actions.toggleHelp;
                continue;
            case GLFW_KEY_TAB:
                if (!repeat && !textInput) ++actions.toggleUi;
                continue;
            default: break;
        }
        if (textInput) continue;
        switch (event.code) {
            case GLFW_KEY_SPACE:
                if (!repeat) {
                    ++actions.togglePlay;
                    playing = !playing;
                }
                break;
            case GLFW_KEY_S: ++actions.steps; break;
            case GLFW_KEY_LEFT:
                --actions.scrub;
                playing = false;
                break;
            case GLFW_KEY_RIGHT:
                if (event.mods & GLFW_MOD_SHIFT) {
                    ++actions.substeps;
                } else {
                    ++actions.scrub;
                }
                playing = false;
                break;
            case GLFW_KEY_PERIOD:
                ++actions.substeps;
                playing = false;
                break;
            case GLFW_KEY_R:
                if (!repeat) actions.restart = true;
                break;
            case GLFW_KEY_C:
            case GLFW_KEY_HOME:
                if (!repeat) actions.resetCamera = true;
                break;
            case GLFW_KEY_P:
                if (repeat) break;
                if (event.mods & GLFW_MOD_SHIFT) {
                    actions.screenshotViewOnly = true;
                } else {
                    actions.screenshot = true;
                }
                break;
            case GLFW_KEY_B:
                if (!repeat) ++actions.toggleBounds;
                break;
            case GLFW_KEY_M:
                if (!repeat) ++actions.toggleCentresOfMass;
                break;
            case GLFW_KEY_V:
                if (!repeat) ++actions.toggleVelocities;
                break;
            default: break;
        }
    }
    return actions;
}

bool grabsBody(int mods) { return (mods & GLFW_MOD_CONTROL) != 0; }

}  // namespace substep::view
