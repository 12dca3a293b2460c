#pragma once
/// Draws captures' frames headless: one GL context (EGL, OSMesa where EGL fails) and renderer
/// for the whole script, an offscreen target remade only when the image size changes.

#include "render/image.h"
#include "render/render_scene.h"

#include <memory>

namespace substep::capture {

class FrameRenderer {
  public:
    /// Creates the headless context. Throws render::ContextError when none can be made.
    FrameRenderer();
    ~FrameRenderer();

    /// `scene` drawn at width x height, rows top to bottom.
    render::Image render(const render::RenderScene& scene, int width, int height);

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace substep::capture
