#pragma once
/// The viewer's keys and mouse buttons: what each does (one table, which the F1 overlay and
/// `substep view --help` both print), and the actions a frame's queued key presses ask for
/// (input_queue.h). Knows nothing of ImGui or the session, so the mapping is tested alone.

#include "view/input_queue.h"

#include <span>
#include <string>

namespace substep::view {

/// One line of the controls' table.
struct ControlHelp {
    const char* keys;
    const char* does;
};

/// Every key and mouse control, in the order the help lists them.
std::span<const ControlHelp> viewControls();
/// The table as text, a control per line ("  Space        play / pause"), for `view --help`.
std::string controlsHelpText();

/// What one frame's key presses ask for. Counts, not flags, where pressing twice in one frame
/// must undo itself (a double tap of Space leaves the play state as it was).
struct KeyActions {
    int togglePlay = 0;
    int steps = 0;          ///< S: one frame each (held, the key repeats)
    int scrub = 0;          ///< Left / Right: frames back / forward through the timeline (repeat)
    int substeps = 0;       ///< . (period) or Shift+Right: one substep each (repeat)
    bool restart = false;   ///< R (also resets the camera)
    bool resetCamera = false;   ///< C or Home
    int toggleUi = 0;       ///< Tab
    int toggleHelp = 0;     ///< F1
    bool screenshot = false;        ///< P: the window as shown
    bool screenshotViewOnly = false;  ///< Shift+P: the 3D view without the panel
    int toggleBounds = 0;          ///< B: the broadphase's boxes
    int toggleCentresOfMass = 0;   ///< M: centres of mass
    int toggleVelocities = 0;      ///< V: linear and angular velocities
};

/// The actions asked by the key presses (and repeats, for stepping) in `events`.
/// With `textInput` (a text box has the keyboard) only F1 counts.
///
/// `drivenKeys` are the GLFW keys the scene binds to knobs (the RC car's WASD and arrows,
/// key_driver.h). While the run plays they drive it and ask nothing of the window; while it is
/// paused they are the window's keys (S steps, Left/Right scrub, Shift+Right steps a substep)
/// and drive nothing. `playing` is whether the run plays before the first event; the events
/// change it in their order (Space toggles it, a substep or a scrub pauses), so a Space then a
/// Shift+Right queued in one slow frame pauses and steps a substep.
KeyActions keyActions(std::span<const InputEvent> events, bool textInput, bool playing = false,
                      std::span<const int> drivenKeys = {});

/// The mouse modifier that grabs a body (Ctrl): a left drag with it held pulls the body under the
/// cursor and does nothing where there is none; without it a left drag orbits.
bool grabsBody(int mods);

}  // namespace substep::view
