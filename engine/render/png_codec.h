#pragma once
/// PNG bytes from an Image and back (stb_image_write / stb_image). Encoding to memory lets the
/// caller write the file whole or not at all (the sandbox's AtomicFile).

#include "render/image.h"

#include <string>
#include <string_view>

namespace substep::render {

/// The image as PNG file bytes (RGBA, 8 bits per channel). Same image, same bytes.
std::string encodePng(const Image& image);

/// Decodes PNG bytes into RGBA. Throws std::runtime_error when they are not a readable PNG.
Image decodePng(std::string_view bytes);

}  // namespace substep::render
