#pragma once
/// The interactive app's OpenGL context: a GLFW window with an OpenGL 3.3 core context, behind
/// the renderer's GlContext interface (render/gl_context.h). The renderer loads its GL functions
/// through glfwGetProcAddress, so the program still links no libGL (render/README.md).

#include "render/gl_context.h"

#include <string>

struct GLFWwindow;

namespace substep::view {

/// Owns GLFW itself (init/terminate) and one window; one instance per process at a time.
class GlfwContext : public render::GlContext {
  public:
    /// Opens a window of `size` screen pixels titled `title` and makes its context current.
    /// Throws render::ContextError naming GLFW's own reason (no display, no GL 3.3 core).
    GlfwContext(const std::string& title, render::PixelSize size);
    ~GlfwContext() override;
    GlfwContext(const GlfwContext&) = delete;
    GlfwContext& operator=(const GlfwContext&) = delete;

    void makeCurrent() override;
    render::GlProcAddress procAddress(const char* name) const override;
    render::PixelSize framebufferSize() const override;
    std::string backendName() const override { return "GLFW"; }

    GLFWwindow* window() const { return window_; }
    bool shouldClose() const;
    /// Shows the frame just drawn.
    void swapBuffers();
    /// Sets whether swapBuffers waits for the display's refresh (off for scripted runs).
    void setVsync(bool on);

  private:
    GLFWwindow* window_ = nullptr;
};

}  // namespace substep::view
