#pragma once
/// A current-able OpenGL context, whatever made it: an EGL surfaceless context, an OSMesa
/// context (both headless, egl_context.h / osmesa_context.h), or later a GLFW window. The
/// renderer sees only this interface, so it never depends on a window system (as Dear ImGui
/// separates its platform backends from its renderer backends).

#include "render/gl_api.h"

#include <stdexcept>
#include <string>

namespace substep::render {

/// No OpenGL context could be created; what() says which backends were tried and why each
/// failed.
class ContextError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

/// Width and height in pixels.
struct PixelSize {
    int width = 0;
    int height = 0;
    friend bool operator==(const PixelSize&, const PixelSize&) = default;
};

class GlContext {
  public:
    virtual ~GlContext() = default;

    /// Makes this context current on the calling thread. Throws ContextError on failure.
    virtual void makeCurrent() = 0;
    /// The address of a GL function of this context, or nullptr.
    virtual GlProcAddress procAddress(const char* name) const = 0;
    /// Size of the context's own framebuffer (the window's); {0, 0} for headless contexts,
    /// which draw into an OffscreenTarget.
    virtual PixelSize framebufferSize() const = 0;
    /// Short name of the backend ("EGL surfaceless", "OSMesa", "GLFW"), for messages.
    virtual std::string backendName() const = 0;

    /// Loads the GL 3.3 table through procAddress (the context must be current).
    GlApi loadApi() const {
        return loadGlApi(
            [](const char* name, void* self) {
                return static_cast<const GlContext*>(self)->procAddress(name);
            },
            const_cast<GlContext*>(this));
    }
};

}  // namespace substep::render
