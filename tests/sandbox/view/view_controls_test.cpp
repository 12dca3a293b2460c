// sandbox/view/view_controls.cpp: the keys' table and what a frame's queued key presses ask for.
// The queue is what keeps a tap shorter than a frame: a press and its release in one frame
// still toggle, two taps in one frame cancel, and a text box keeps the letters to itself.

#include "view/view_controls.h"

#include <GLFW/glfw3.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace substep::view {
namespace {

InputEvent key(int code, int action = GLFW_PRESS, int mods = 0) {
    return {InputEvent::Kind::Key, code, action, mods, 0.0, 0.0};
}

TEST(ViewControlsTest, ATapWithinOneFrameTogglesPlay) {
    const std::vector<InputEvent> tap{key(GLFW_KEY_SPACE), key(GLFW_KEY_SPACE, GLFW_RELEASE)};
    EXPECT_EQ(keyActions(tap, false).togglePlay, 1);
    // Two taps in one slow frame: pause and resume, so the play state ends as it was.
    const std::vector<InputEvent> twice{key(GLFW_KEY_SPACE), key(GLFW_KEY_SPACE, GLFW_RELEASE), key(GLFW_KEY_SPACE),
                                        key(GLFW_KEY_SPACE, GLFW_RELEASE)};
    EXPECT_EQ(keyActions(twice, false).togglePlay % 2, 0);
    // A held Space repeats, but only the press toggles.
    const std::vector<InputEvent> held{key(GLFW_KEY_SPACE), key(GLFW_KEY_SPACE, GLFW_REPEAT),
                                       key(GLFW_KEY_SPACE, GLFW_REPEAT)};
    EXPECT_EQ(keyActions(held, false).togglePlay, 1);
}

TEST(ViewControlsTest, StepsCountEveryPressAndRepeat) {
    const std::vector<InputEvent> events{key(GLFW_KEY_S), key(GLFW_KEY_S, GLFW_RELEASE), key(GLFW_KEY_S),
                                         key(GLFW_KEY_S, GLFW_REPEAT), key(GLFW_KEY_S, GLFW_RELEASE)};
    EXPECT_EQ(keyActions(events, false).steps, 3);
}

TEST(ViewControlsTest, LeftAndRightScrubTheTimelineAFrameAPressOrRepeat) {
    const std::vector<InputEvent> events{key(GLFW_KEY_LEFT), key(GLFW_KEY_LEFT, GLFW_REPEAT), key(GLFW_KEY_LEFT, GLFW_RELEASE),
                                         key(GLFW_KEY_RIGHT), key(GLFW_KEY_LEFT)};
    EXPECT_EQ(keyActions(events, false).scrub, -2);
    EXPECT_EQ(keyActions(events, true).scrub, 0) << "a text box keeps the arrows";
}

TEST(ViewControlsTest, EachKeyAsksForItsAction) {
    EXPECT_TRUE(keyActions(std::vector{key(GLFW_KEY_R)}, false).restart);
    EXPECT_TRUE(keyActions(std::vector{key(GLFW_KEY_C)}, false).resetCamera);
    EXPECT_TRUE(keyActions(std::vector{key(GLFW_KEY_HOME)}, false).resetCamera);
    EXPECT_EQ(keyActions(std::vector{key(GLFW_KEY_TAB)}, false).toggleUi, 1);
    EXPECT_EQ(keyActions(std::vector{key(GLFW_KEY_F1)}, false).toggleHelp, 1);
    const KeyActions shot = keyActions(std::vector{key(GLFW_KEY_P)}, false);
    EXPECT_TRUE(shot.screenshot);
    EXPECT_FALSE(shot.screenshotViewOnly);
    const KeyActions viewOnly = keyActions(std::vector{key(GLFW_KEY_P, GLFW_PRESS, GLFW_MOD_SHIFT)}, false);
    EXPECT_TRUE(viewOnly.screenshotViewOnly);
    EXPECT_FALSE(viewOnly.screenshot);
    // Releases and unbound keys ask for nothing.
    const KeyActions none = keyActions(std::vector{key(GLFW_KEY_R, GLFW_RELEASE), key(GLFW_KEY_Q)}, false);
    EXPECT_FALSE(none.restart);
    EXPECT_EQ(none.steps, 0);
    EXPECT_EQ(none.togglePlay, 0);
}

TEST(ViewControlsTest, LayerKeysCountPressesNotRepeatsAndYieldToATextBox) {
    const std::vector<InputEvent> presses{key(GLFW_KEY_B), key(GLFW_KEY_M), key(GLFW_KEY_V), key(GLFW_KEY_V),
                                          key(GLFW_KEY_B, GLFW_REPEAT), key(GLFW_KEY_M, GLFW_RELEASE)};
    const KeyActions actions = keyActions(presses, false);
    EXPECT_EQ(actions.toggleBounds, 1);
    EXPECT_EQ(actions.toggleCentresOfMass, 1);
    EXPECT_EQ(actions.toggleVelocities, 2);  // two taps in a frame: an even count, no change
    const KeyActions typed = keyActions(presses, true);  // "bmvv" into the column filter
    EXPECT_EQ(typed.toggleBounds + typed.toggleCentresOfMass + typed.toggleVelocities, 0);
}

TEST(ViewControlsTest, ATextBoxKeepsEveryKeyButF1) {
    const std::vector<InputEvent> typing{key(GLFW_KEY_SPACE), key(GLFW_KEY_S), key(GLFW_KEY_R), key(GLFW_KEY_P),
                                         key(GLFW_KEY_F1), key(GLFW_KEY_TAB)};
    const KeyActions actions = keyActions(typing, true);
    EXPECT_EQ(actions.togglePlay, 0);
    EXPECT_EQ(actions.steps, 0);
    EXPECT_FALSE(actions.restart);
    EXPECT_FALSE(actions.screenshot);
    EXPECT_EQ(actions.toggleHelp, 1);
    EXPECT_EQ(actions.toggleUi, 0);  // Tab moves between the panel's fields
}

TEST(ViewControlsTest, MouseEventsAreNotKeys) {
    const std::vector<InputEvent> clicks{{InputEvent::Kind::MouseButton, GLFW_KEY_SPACE, GLFW_PRESS, 0, 1.0, 2.0}};
    EXPECT_EQ(keyActions(clicks, false).togglePlay, 0);
}

TEST(ViewControlsTest, CtrlGrabsAndNothingElseDoes) {
    EXPECT_TRUE(grabsBody(GLFW_MOD_CONTROL));
    EXPECT_TRUE(grabsBody(GLFW_MOD_CONTROL | GLFW_MOD_SHIFT));
    EXPECT_FALSE(grabsBody(0));
    EXPECT_FALSE(grabsBody(GLFW_MOD_SHIFT));
    EXPECT_FALSE(grabsBody(GLFW_MOD_ALT));
}

TEST(ViewControlsTest, DrivenKeysDriveWhilePlayingAndAreTheWindowsWhilePaused) {
    // The RC car binds WASD and the arrows: playing, they steer and ask nothing of the window
    // (Shift+Right used to steer and step a substep at once); paused, they step and scrub.
    const std::vector<int> driven{GLFW_KEY_W, GLFW_KEY_A, GLFW_KEY_S, GLFW_KEY_D,
                                  GLFW_KEY_UP, GLFW_KEY_DOWN, GLFW_KEY_LEFT, GLFW_KEY_RIGHT};
    const std::vector shiftRight{key(GLFW_KEY_RIGHT, GLFW_PRESS, GLFW_MOD_SHIFT)};
    EXPECT_EQ(keyActions(shiftRight, false, true, driven).substeps, 0);
    EXPECT_EQ(keyActions(shiftRight, false, false, driven).substeps, 1);
    EXPECT_EQ(keyActions(shiftRight, false, true).substeps, 1) << "no scene keys: the window's";
    const std::vector arrows{key(GLFW_KEY_LEFT), key(GLFW_KEY_S), key(GLFW_KEY_LEFT, GLFW_REPEAT)};
    const KeyActions playing = keyActions(arrows, false, true, driven);
    EXPECT_EQ(playing.scrub, 0);
    EXPECT_EQ(playing.steps, 0);
    const KeyActions paused = keyActions(arrows, false, false, driven);
    EXPECT_EQ(paused.scrub, -2);
    EXPECT_EQ(paused.steps, 1);
    // The period is no driving key: it pauses and steps a substep while playing, and the
    // arrows after it in the same frame are then the window's.
    const std::vector periodThenRight{key(GLFW_KEY_PERIOD), key(GLFW_KEY_RIGHT, GLFW_PRESS, GLFW_MOD_SHIFT)};
    EXPECT_EQ(keyActions(periodThenRight, false, true, driven).substeps, 2);
    // Space then Shift+Right queued in one slow frame: paused first, so a substep.
    const std::vector spaceThenRight{key(GLFW_KEY_SPACE), key(GLFW_KEY_RIGHT, GLFW_PRESS, GLFW_MOD_SHIFT)};
    const KeyActions both = keyActions(spaceThenRight, false, true, driven);
    EXPECT_EQ(both.togglePlay, 1);
    EXPECT_EQ(both.substeps, 1);
    // And the other way round: resumed first, the arrow steers.
    EXPECT_EQ(keyActions(spaceThenRight, false, false, driven).substeps, 0);
}

TEST(ViewControlsTest, TheHelpTextListsEveryControl) {
    const std::string text = controlsHelpText();
    ASSERT_FALSE(viewControls().empty());
    for (const ControlHelp& control : viewControls()) {
        EXPECT_NE(text.find(control.keys), std::string::npos) << control.keys;
        EXPECT_NE(text.find(control.does), std::string::npos) << control.does;
    }
    for (const char* expected : {"Space", "F1", "Tab", "Shift+P", "Ctrl + left drag"}) {
        EXPECT_NE(text.find(expected), std::string::npos) << expected;
    }
}

}  // namespace
}  // namespace substep::view
