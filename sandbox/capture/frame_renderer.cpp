#include "capture/frame_renderer.h"

#include "render/headless_context.h"
#include "render/offscreen_target.h"
#include "render/renderer.h"

namespace substep::capture {

struct FrameRenderer::Impl {
    std::unique_ptr<render::GlContext> context = render::createHeadlessContext();
    render::GlApi gl = context->loadApi();
    render::Renderer renderer{gl};
    std::unique_ptr<render::OffscreenTarget> target;
    int width = 0;
    int height = 0;
};

FrameRenderer::FrameRenderer() : impl_(std::make_unique<Impl>()) {}

FrameRenderer::~FrameRenderer() = default;

render::Image FrameRenderer::render(const render::RenderScene& scene, int width, int height) {
    Impl& impl = *impl_;
    if (!impl.target || impl.width != width || impl.height != height) {
        impl.target.reset();
        impl.target =
            std::make_unique<render::OffscreenTarget>(impl.gl, render::PixelSize{width, height});
        impl.width = width;
        impl.height = height;
    }
    impl.renderer.render(scene, impl.target->target());
    return impl.target->readPixels();
}

}  // namespace substep::capture
