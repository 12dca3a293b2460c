#pragma once
/// The headless context the `render` command and the tests use: EGL surfaceless first, OSMesa
/// when EGL fails. SUBSTEP_GL_BACKEND=egl or =osmesa picks one backend without the other (to test
/// the fallback, or to work around a broken driver).

#include "render/gl_context.h"

#include <memory>

namespace substep::render {

/// Creates a current headless context. Throws ContextError listing every backend tried and why
/// it failed.
std::unique_ptr<GlContext> createHeadlessContext();

}  // namespace substep::render
