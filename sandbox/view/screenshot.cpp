#include "view/screenshot.h"

#include "atomic_file.h"

#include "render/png_codec.h"

#include <cctype>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace substep::view {

render::Image readBackBuffer(const render::GlApi& gl, const render::RenderTarget& area) {
    const int width = area.size.width;
    const int height = area.size.height;
    render::Image image{width, height, std::vector<uint8_t>(static_cast<std::size_t>(width) * height * 4)};
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl.ReadBuffer(GL_BACK);
    gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
    std::vector<uint8_t> bottomUp(image.rgba.size());
    gl.ReadPixels(area.originX, area.originY, width, height, GL_RGBA, GL_UNSIGNED_BYTE, bottomUp.data());
    if (const GLenum error = gl.GetError(); error != GL_NO_ERROR) {
        throw std::runtime_error("reading the window's pixels failed: " + render::glErrorName(error));
    }
    const std::size_t row = static_cast<std::size_t>(width) * 4;
    for (int y = 0; y < height; ++y) {
        std::memcpy(&image.rgba[y * row], &bottomUp[(height - 1 - y) * row], row);
    }
    // What the blending of the panel leaves in alpha is not part of the picture.
    for (std::size_t i = 3; i < image.rgba.size(); i += 4) image.rgba[i] = 255;
    return image;
}

std::filesystem::path screenshotPath(const std::filesystem::path& folder, const std::string& sceneLabel,
                                     long long frame) {
    std::string scene;
    for (const char c : std::filesystem::path(sceneLabel).stem().string()) {
        const bool kept = std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_' || c == '-';
        scene += kept ? c : '_';
    }
    if (scene.empty()) scene = "scene";
    const std::string stem = "substep_" + scene + "_f" + std::to_string(frame);
    std::filesystem::path path = folder / (stem + ".png");
    for (int copy = 2; std::filesystem::exists(path); ++copy) {
        path = folder / (stem + "_" + std::to_string(copy) + ".png");
    }
    return path;
}

void saveScreenshot(const render::Image& image, const std::filesystem::path& path) {
    AtomicFile file(path.string());
    file.write(render::encodePng(image));
    file.commit();
}

}  // namespace substep::view
