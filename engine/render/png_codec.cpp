#include "render/png_codec.h"

#include <stb_image.h>
#include <stb_image_write.h>

#include <cstdlib>
#include <stdexcept>

namespace substep::render {

std::string encodePng(const Image& image) {
    std::string bytes;
    const auto append = [](void* context, void* data, int size) {
        static_cast<std::string*>(context)->append(static_cast<const char*>(data),
                                                   static_cast<std::size_t>(size));
    };
    if (stbi_write_png_to_func(append, &bytes, image.width, image.height, 4, image.rgba.data(),
                               image.width * 4) == 0) {
        throw std::runtime_error("PNG encoding failed");
    }
    return bytes;
}

Image decodePng(std::string_view bytes) {
    int width = 0;
    int height = 0;
    int channels = 0;
    unsigned char* pixels = stbi_load_from_memory(reinterpret_cast<const unsigned char*>(bytes.data()),
                                                  static_cast<int>(bytes.size()), &width, &height,
                                                  &channels, 4);
    if (pixels == nullptr) {
        throw std::runtime_error(std::string("not a readable PNG: ") + stbi_failure_reason());
    }
    Image image{.width = width, .height = height};
    image.rgba.assign(pixels, pixels + static_cast<std::size_t>(width) * height * 4);
    stbi_image_free(pixels);
    return image;
}

}  // namespace substep::render
