#include "render/offscreen_target.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

namespace substep::render {

OffscreenTarget::OffscreenTarget(const GlApi& gl, PixelSize size, int samples) : gl_(gl), size_(size) {
    GLint maxSize = 0;
    GLint maxSamples = 0;
    gl_.GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &maxSize);
    gl_.GetIntegerv(GL_MAX_SAMPLES, &maxSamples);
    if (size.width < 1 || size.height < 1 || size.width > maxSize || size.height > maxSize) {
        throw std::runtime_error("image size " + std::to_string(size.width) + "x" +
                                 std::to_string(size.height) + " is outside 1.." +
                                 std::to_string(maxSize) + " per side on this OpenGL device");
    }
    samples_ = std::clamp(samples, 0, static_cast<int>(maxSamples));

    const auto renderbuffer = [&](GLuint& id, GLenum format, int sampleCount) {
        gl_.GenRenderbuffers(1, &id);
        gl_.BindRenderbuffer(GL_RENDERBUFFER, id);
        gl_.RenderbufferStorageMultisample(GL_RENDERBUFFER, sampleCount, format, size.width, size.height);
    };
    renderbuffer(colourBuffer_, GL_RGBA8, samples_);
    renderbuffer(depthBuffer_, GL_DEPTH_COMPONENT24, samples_);
    renderbuffer(resolveBuffer_, GL_RGBA8, 0);

    gl_.GenFramebuffers(1, &multisampledFramebuffer_);
    gl_.BindFramebuffer(GL_FRAMEBUFFER, multisampledFramebuffer_);
    gl_.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colourBuffer_);
    gl_.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depthBuffer_);
    const GLenum multisampledStatus = gl_.CheckFramebufferStatus(GL_FRAMEBUFFER);

    gl_.GenFramebuffers(1, &resolveFramebuffer_);
    gl_.BindFramebuffer(GL_FRAMEBUFFER, resolveFramebuffer_);
    gl_.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, resolveBuffer_);
    const GLenum resolveStatus = gl_.CheckFramebufferStatus(GL_FRAMEBUFFER);
    gl_.BindFramebuffer(GL_FRAMEBUFFER, 0);

    if (multisampledStatus != GL_FRAMEBUFFER_COMPLETE || resolveStatus != GL_FRAMEBUFFER_COMPLETE) {
        release();
        throw std::runtime_error("offscreen framebuffer of " + std::to_string(size.width) + "x" +
                                 std::to_string(size.height) + " is incomplete");
    }
}

OffscreenTarget::~OffscreenTarget() { release(); }

void OffscreenTarget::release() {
    gl_.DeleteFramebuffers(1, &multisampledFramebuffer_);
    gl_.DeleteFramebuffers(1, &resolveFramebuffer_);
    gl_.DeleteRenderbuffers(1, &colourBuffer_);
    gl_.DeleteRenderbuffers(1, &depthBuffer_);
    gl_.DeleteRenderbuffers(1, &resolveBuffer_);
    multisampledFramebuffer_ = resolveFramebuffer_ = colourBuffer_ = depthBuffer_ = resolveBuffer_ = 0;
}

void OffscreenTarget::resolveInto(GLuint framebuffer, const RenderTarget& from, const RenderTarget& to) const {
    const bool scaled = from.size.width != to.size.width || from.size.height != to.size.height;
    gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, multisampledFramebuffer_);
    gl_.BindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer);
    gl_.BlitFramebuffer(from.originX, from.originY, from.originX + from.size.width, from.originY + from.size.height,
                        to.originX, to.originY, to.originX + to.size.width, to.originY + to.size.height,
                        GL_COLOR_BUFFER_BIT, scaled ? GL_LINEAR : GL_NEAREST);
    gl_.BindFramebuffer(GL_FRAMEBUFFER, framebuffer);
}

Image OffscreenTarget::readPixels() const {
    // Resolve the samples first: glReadPixels cannot read a multisampled buffer.
    gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, multisampledFramebuffer_);
    gl_.BindFramebuffer(GL_DRAW_FRAMEBUFFER, resolveFramebuffer_);
    gl_.BlitFramebuffer(0, 0, size_.width, size_.height, 0, 0, size_.width, size_.height,
                        GL_COLOR_BUFFER_BIT, GL_NEAREST);
    gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, resolveFramebuffer_);
    gl_.PixelStorei(GL_PACK_ALIGNMENT, 1);
    Image image{.width = size_.width, .height = size_.height};
    const std::size_t rowBytes = static_cast<std::size_t>(size_.width) * 4;
    std::vector<uint8_t> bottomUp(rowBytes * static_cast<std::size_t>(size_.height));
    gl_.ReadPixels(0, 0, size_.width, size_.height, GL_RGBA, GL_UNSIGNED_BYTE, bottomUp.data());
    gl_.BindFramebuffer(GL_FRAMEBUFFER, 0);
    const GLenum error = gl_.GetError();
    if (error != GL_NO_ERROR) throw std::runtime_error("reading the frame back: " + glErrorName(error));

    // GL rows start at the bottom; PNG rows at the top.
    image.rgba.resize(bottomUp.size());
    for (int y = 0; y < size_.height; ++y) {
        std::memcpy(&image.rgba[static_cast<std::size_t>(y) * rowBytes],
                    &bottomUp[static_cast<std::size_t>(size_.height - 1 - y) * rowBytes], rowBytes);
    }
    // The frame is opaque; a stray alpha from blending must not make the PNG translucent.
    for (std::size_t i = 3; i < image.rgba.size(); i += 4) image.rgba[i] = 255;
    return image;
}

}  // namespace substep::render
