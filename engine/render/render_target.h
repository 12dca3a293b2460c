#pragma once
/// Where a frame is drawn: a framebuffer object of the current context and its size. A window's
/// default framebuffer is {0, its size}; OffscreenTarget gives a multisampled one.

#include "render/gl_context.h"

namespace substep::render {

struct RenderTarget {
    GLuint framebuffer = 0;
    PixelSize size;
};

}  // namespace substep::render
