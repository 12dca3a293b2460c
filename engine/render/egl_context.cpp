#include "render/egl_context.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstdio>
#include <string>

namespace substep::render {
namespace {

std::string eglFailure(const char* step) {
    char code[16];
    std::snprintf(code, sizeof code, "0x%04X", static_cast<unsigned>(eglGetError()));
    return std::string("EGL: ") + step + " failed (error " + code + ")";
}

class EglContext final : public GlContext {
  public:
    EglContext() {
        // The surfaceless platform needs no display server and no device file.
        const auto getPlatformDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
            eglGetProcAddress("eglGetPlatformDisplayEXT"));
        if (getPlatformDisplay == nullptr) {
            throw ContextError("EGL: eglGetPlatformDisplayEXT is missing (no EGL_EXT_platform_base)");
        }
        display_ = getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        if (display_ == EGL_NO_DISPLAY) {
            throw ContextError(eglFailure("eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA)"));
        }
        EGLint major = 0;
        EGLint minor = 0;
        if (eglInitialize(display_, &major, &minor) != EGL_TRUE) {
            display_ = EGL_NO_DISPLAY;
            throw ContextError(eglFailure("eglInitialize on the surfaceless platform"));
        }
        try {
            create();
        } catch (...) {
            release();
            throw;
        }
    }

    ~EglContext() override { release(); }

    void makeCurrent() override {
        if (eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_) != EGL_TRUE) {
            throw ContextError(eglFailure("eglMakeCurrent (surfaceless)"));
        }
    }

    GlProcAddress procAddress(const char* name) const override {
        return reinterpret_cast<GlProcAddress>(eglGetProcAddress(name));
    }

    PixelSize framebufferSize() const override { return {}; }
    std::string backendName() const override { return "EGL surfaceless"; }

  private:
    void create() {
        if (eglBindAPI(EGL_OPENGL_API) != EGL_TRUE) throw ContextError(eglFailure("eglBindAPI(OpenGL)"));
        const EGLint configAttributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
        EGLConfig config = nullptr;
        EGLint count = 0;
        if (eglChooseConfig(display_, configAttributes, &config, 1, &count) != EGL_TRUE || count == 0) {
            // A context without a config is fine for surfaceless drawing into FBOs.
            config = static_cast<EGLConfig>(nullptr);  // EGL_NO_CONFIG_KHR
        }
        const EGLint contextAttributes[] = {
            EGL_CONTEXT_MAJOR_VERSION, 3,
            EGL_CONTEXT_MINOR_VERSION, 3,
            EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
            EGL_NONE};
        context_ = eglCreateContext(display_, config, EGL_NO_CONTEXT, contextAttributes);
        if (context_ == EGL_NO_CONTEXT) throw ContextError(eglFailure("eglCreateContext (OpenGL 3.3 core)"));
        makeCurrent();
    }

    void release() {
        if (display_ == EGL_NO_DISPLAY) return;
        eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (context_ != EGL_NO_CONTEXT) eglDestroyContext(display_, context_);
        eglTerminate(display_);
        display_ = EGL_NO_DISPLAY;
        context_ = EGL_NO_CONTEXT;
    }

    EGLDisplay display_ = EGL_NO_DISPLAY;
    EGLContext context_ = EGL_NO_CONTEXT;
};

}  // namespace

std::unique_ptr<GlContext> createEglContext() { return std::make_unique<EglContext>(); }

}  // namespace substep::render
