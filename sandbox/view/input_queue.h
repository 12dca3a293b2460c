#pragma once
/// Key presses and mouse clicks as GLFW reports them, queued until the frame loop reads them, so
/// a tap shorter than a frame is never lost. Dear ImGui 1.86 (Debian 12's) keeps only which keys
/// are down at the start of a frame: a Space pressed and released within one 200 ms frame of a
/// software-rendered scene was never seen. The queue's callbacks are installed before ImGui's
/// backend, which chains to them, so ImGui still gets every event.
///
/// It also counts every event (cursor motion, resizes and exposures too), so a paused window
/// can sleep until something happens instead of redrawing the same picture.

#include <cstdint>
#include <vector>

struct GLFWwindow;

namespace substep::view {

/// One queued press or release.
struct InputEvent {
    enum class Kind { Key, MouseButton };
    Kind kind = Kind::Key;
    int code = 0;     ///< GLFW key or mouse button
    int action = 0;   ///< GLFW_PRESS, GLFW_RELEASE or GLFW_REPEAT
    int mods = 0;     ///< GLFW_MOD_* bits held
    double x = 0.0;   ///< cursor position at the event (screen coordinates), for mouse buttons
    double y = 0.0;
};

class InputQueue {
  public:
    /// Installs the callbacks on `window`; call before ImGui_ImplGlfw_InitForOpenGL so that its
    /// callbacks chain to these. One queue per window; the window keeps a pointer to it.
    explicit InputQueue(GLFWwindow* window);
    ~InputQueue();
    InputQueue(const InputQueue&) = delete;
    InputQueue& operator=(const InputQueue&) = delete;

    /// The events queued since the last call, oldest first; the queue is then empty.
    const std::vector<InputEvent>& take();
    /// Events of any kind (motion, wheel, characters, resizes, exposures) seen so far.
    std::uint64_t eventCount() const { return eventCount_; }

    /// Adds an event as a callback does (for tests and the callbacks themselves).
    void push(const InputEvent& event);
    void countEvent() { ++eventCount_; }

  private:
    GLFWwindow* window_;
    std::vector<InputEvent> pending_;
    std::vector<InputEvent> taken_;
    std::uint64_t eventCount_ = 0;
};

}  // namespace substep::view
