#pragma once
/// Headless OpenGL 3.3 core context from OSMesa, the fallback where EGL cannot make one.
///
/// libOSMesa is opened with dlopen when this is first called rather than linked: it exports its
/// own gl* entry points, which must not meet GLVND's in one link (DESIGN.md), and a program that
/// never falls back then never loads it. Drawing goes to an OffscreenTarget like EGL's; OSMesa's
/// own colour buffer is only the 1x1 surface it needs to be made current.

#include "render/gl_context.h"

#include <memory>

namespace substep::render {

/// Creates the context and makes it current. Throws ContextError when libOSMesa is missing or
/// cannot create a 3.3 core context.
std::unique_ptr<GlContext> createOsMesaContext();

}  // namespace substep::render
