#pragma once
/// A multisampled framebuffer (colour + depth renderbuffers) to draw into without a window, and
/// the resolve into a single-sampled one that is read back as an Image. Every headless backend
/// draws here, so reading pixels is the same GL code whatever made the context.

#include "render/gl_api.h"
#include "render/image.h"
#include "render/render_target.h"

namespace substep::render {

class OffscreenTarget {
  public:
    /// Allocates the buffers on the current context. `samples` is capped by GL_MAX_SAMPLES.
    /// Throws std::runtime_error when the size exceeds GL_MAX_RENDERBUFFER_SIZE or the
    /// framebuffer is incomplete.
    OffscreenTarget(const GlApi& gl, PixelSize size, int samples = 4);
    ~OffscreenTarget();
    OffscreenTarget(const OffscreenTarget&) = delete;
    OffscreenTarget& operator=(const OffscreenTarget&) = delete;

    /// The multisampled framebuffer to pass to Renderer::render.
    RenderTarget target() const { return {multisampledFramebuffer_, size_}; }
    /// Resolves the samples and reads the frame back, rows top to bottom.
    Image readPixels() const;
    /// Resolves the area `from` of this target's framebuffer into the area `to` of
    /// `framebuffer`, scaled (bilinear) when the sizes differ, which needs a target of one
    /// sample: the interactive app draws its scene here and shows it in the window's default
    /// framebuffer (0).
    void resolveInto(GLuint framebuffer, const RenderTarget& from, const RenderTarget& to) const;
    /// Samples per pixel actually allocated.
    int samples() const { return samples_; }

  private:
    void release();

    const GlApi& gl_;
    PixelSize size_;
    int samples_ = 0;
    GLuint multisampledFramebuffer_ = 0;
    GLuint colourBuffer_ = 0;
    GLuint depthBuffer_ = 0;
    GLuint resolveFramebuffer_ = 0;
    GLuint resolveBuffer_ = 0;
};

}  // namespace substep::render
