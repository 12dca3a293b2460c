#include "view/glfw_context.h"

#include <GLFW/glfw3.h>

namespace substep::view {

namespace {

/// GLFW reports failures through a callback; the last message is kept so the exception can say
/// why (e.g. "X11: Failed to open display") instead of just "failed".
std::string& lastGlfwError() {
    static std::string message;
    return message;
}

void recordGlfwError(int /*code*/, const char* description) { lastGlfwError() = description ? description : ""; }

}  // namespace

GlfwContext::GlfwContext(const std::string& title, render::PixelSize size) {
    glfwSetErrorCallback(recordGlfwError);
    if (glfwInit() != GLFW_TRUE) {
        throw render::ContextError("GLFW could not start: " + lastGlfwError());
    }
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    // No multisampling of the window itself: the scene is drawn into a multisampled offscreen
    // buffer as the quality level asks (render_quality.h) and resolved into the window, so the
    // level can change without a new window, and the panel is not drawn multisampled.
    glfwWindowHint(GLFW_SAMPLES, 0);
    window_ = glfwCreateWindow(size.width, size.height, title.c_str(), nullptr, nullptr);
    if (window_ == nullptr) {
        const std::string reason = lastGlfwError();
        glfwTerminate();
        throw render::ContextError("GLFW could not open an OpenGL 3.3 core window: " + reason);
    }
    glfwMakeContextCurrent(window_);
}

GlfwContext::~GlfwContext() {
    glfwDestroyWindow(window_);
    glfwTerminate();
}

void GlfwContext::makeCurrent() { glfwMakeContextCurrent(window_); }

render::GlProcAddress GlfwContext::procAddress(const char* name) const { return glfwGetProcAddress(name); }

render::PixelSize GlfwContext::framebufferSize() const {
    render::PixelSize size;
    glfwGetFramebufferSize(window_, &size.width, &size.height);
    return size;
}

bool GlfwContext::shouldClose() const { return glfwWindowShouldClose(window_) == GLFW_TRUE; }

void GlfwContext::swapBuffers() { glfwSwapBuffers(window_); }

void GlfwContext::setVsync(bool on) { glfwSwapInterval(on ? 1 : 0); }

}  // namespace substep::view
