#pragma once
/// An 8-bit RGBA image, rows top to bottom (as PNG stores them, unlike GL's bottom-up reads).

#include <cstdint>
#include <vector>

namespace substep::render {

struct Image {
    int width = 0;
    int height = 0;
    std::vector<uint8_t> rgba;  ///< width * height * 4 bytes

    const uint8_t* pixel(int x, int y) const { return &rgba[(static_cast<std::size_t>(y) * width + x) * 4]; }
};

}  // namespace substep::render
