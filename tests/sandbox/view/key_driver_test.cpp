// Tests sandbox/view/key_driver.cpp: the knobs a scene binds to keys are driven only while the
// run plays. Paused, a held arrow (the RC car's steering) leaves the knob and the timeline alone,
// so the window's use of the key (Shift+Right steps a substep, Left/Right scrub) changes nothing
// else; playing again, the held key steers.

#include "view/key_driver.h"

#include "scene_source.h"

#include <GLFW/glfw3.h>
#include <gtest/gtest.h>
#include <imgui.h>

namespace substep::view {
namespace {

/// A Dear ImGui context whose keyboard state the test sets (the driver reads ImGui's).
class ImGuiKeys {
  public:
    ImGuiKeys() { ImGui::CreateContext(); }
    ~ImGuiKeys() { ImGui::DestroyContext(); }
    ImGuiKeys(const ImGuiKeys&) = delete;
    ImGuiKeys& operator=(const ImGuiKeys&) = delete;
    void hold(int key, bool down) { ImGui::GetIO().KeysDown[key] = down; }
};

double knobValue(CompareSession& session, const char* name) {
    const SceneKnob* knob = session.first().script()->findKnob(name);
    return knob != nullptr ? knob->value : -1e300;
}

TEST(KeyDriver, ABoundKeyDrivesOnlyWhileTheRunPlays) {
    ImGuiKeys keys;
    CompareSession session(resolveScene("rc_car"), 16.0f / 9.0f);
    ASSERT_NE(session.first().script(), nullptr);
    ASSERT_NE(session.first().script()->findKnob("steer"), nullptr);
    KeyDriver driver;
    const std::vector<int> bound = driver.boundKeys(session);
    EXPECT_NE(std::find(bound.begin(), bound.end(), GLFW_KEY_RIGHT), bound.end());
    EXPECT_NE(std::find(bound.begin(), bound.end(), GLFW_KEY_W), bound.end());
    EXPECT_EQ(std::find(bound.begin(), bound.end(), GLFW_KEY_PERIOD), bound.end());

    session.playback().playing = false;
    for (int frame = 0; frame < 3; ++frame) session.stepOnce();
    const double rest = knobValue(session, "steer");
    const long long firstKept = session.first().timeline().firstFrame();
    keys.hold(GLFW_KEY_RIGHT, true);
    driver.update(session);
    EXPECT_EQ(knobValue(session, "steer"), rest) << "paused: Right is the window's key";
    EXPECT_EQ(session.first().timeline().firstFrame(), firstKept) << "and the history is kept";
    session.stepSubstep();  // what Shift+Right asks for while paused
    driver.update(session);
    EXPECT_EQ(knobValue(session, "steer"), rest);
    EXPECT_EQ(session.first().frameSubstepsDone(), 1);

    session.playback().playing = true;
    driver.update(session);
    EXPECT_NE(knobValue(session, "steer"), rest) << "playing: Right steers";
    keys.hold(GLFW_KEY_RIGHT, false);
    driver.update(session);
    EXPECT_EQ(knobValue(session, "steer"), rest) << "let go: back to rest";
}

}  // namespace
}  // namespace substep::view
