#include "view/input_queue.h"

#include <GLFW/glfw3.h>

namespace substep::view {

namespace {

InputQueue* queueOf(GLFWwindow* window) { return static_cast<InputQueue*>(glfwGetWindowUserPointer(window)); }

void onKey(GLFWwindow* window, int key, int /*scancode*/, int action, int mods) {
    if (InputQueue* queue = queueOf(window)) queue->push({InputEvent::Kind::Key, key, action, mods, 0.0, 0.0});
}

void onMouseButton(GLFWwindow* window, int button, int action, int mods) {
    InputQueue* queue = queueOf(window);
    if (queue == nullptr) return;
    double x = 0.0;
    double y = 0.0;
    glfwGetCursorPos(window, &x, &y);
    queue->push({InputEvent::Kind::MouseButton, button, action, mods, x, y});
}

void onAnything(GLFWwindow* window) {
    if (InputQueue* queue = queueOf(window)) queue->countEvent();
}

}  // namespace

InputQueue::InputQueue(GLFWwindow* window) : window_(window) {
    glfwSetWindowUserPointer(window, this);
    glfwSetKeyCallback(window, onKey);
    glfwSetMouseButtonCallback(window, onMouseButton);
    glfwSetCursorPosCallback(window, [](GLFWwindow* w, double, double) { onAnything(w); });
    glfwSetScrollCallback(window, [](GLFWwindow* w, double, double) { onAnything(w); });
    glfwSetCharCallback(window, [](GLFWwindow* w, unsigned int) { onAnything(w); });
    glfwSetCursorEnterCallback(window, [](GLFWwindow* w, int) { onAnything(w); });
    glfwSetWindowFocusCallback(window, [](GLFWwindow* w, int) { onAnything(w); });
    glfwSetFramebufferSizeCallback(window, [](GLFWwindow* w, int, int) { onAnything(w); });
    glfwSetWindowRefreshCallback(window, [](GLFWwindow* w) { onAnything(w); });
}

InputQueue::~InputQueue() { glfwSetWindowUserPointer(window_, nullptr); }

void InputQueue::push(const InputEvent& event) {
    pending_.push_back(event);
    ++eventCount_;
}

const std::vector<InputEvent>& InputQueue::take() {
    taken_.clear();
    taken_.swap(pending_);
    return taken_;
}

}  // namespace substep::view
