#pragma once
/// Where a frame is drawn: a framebuffer object of the current context and the area of it drawn
/// into. A window's default framebuffer is {0, its size}; OffscreenTarget gives a multisampled
/// one. An origin other than (0, 0) draws into a part of the framebuffer only, as the viewer's
/// compare mode draws two runs side by side.

#include "render/gl_context.h"

namespace substep::render {

struct RenderTarget {
    GLuint framebuffer = 0;
    PixelSize size;  ///< of the area drawn into
    int originX = 0;  ///< the area's lower-left corner in the framebuffer (pixels, GL's y up)
    int originY = 0;
};

}  // namespace substep::render
