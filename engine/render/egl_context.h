#pragma once
/// Headless OpenGL 3.3 core context on EGL's surfaceless platform (EGL_MESA_platform_surfaceless):
/// no display, no window, no pbuffer. It has no default framebuffer, so everything is drawn into
/// an OffscreenTarget. On a machine without a GPU, Mesa gives llvmpipe.

#include "render/gl_context.h"

#include <memory>

namespace substep::render {

/// Creates the context and makes it current. Throws ContextError saying which EGL step failed.
std::unique_ptr<GlContext> createEglContext();

}  // namespace substep::render
