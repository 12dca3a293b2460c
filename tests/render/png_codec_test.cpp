// Tests engine/render/png_codec.cpp: PNG bytes round-trip exactly, repeat exactly, and bad bytes
// are an error rather than a crash.

#include "render/png_codec.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace substep::render {
namespace {

Image gradient(int width, int height) {
    Image image{.width = width, .height = height};
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            image.rgba.insert(image.rgba.end(), {static_cast<uint8_t>(x * 7), static_cast<uint8_t>(y * 11),
                                                 static_cast<uint8_t>(x + y), 255});
        }
    }
    return image;
}

TEST(PngCodec, RoundTripsPixelsExactly) {
    const Image image = gradient(17, 9);
    const std::string bytes = encodePng(image);
    ASSERT_GT(bytes.size(), 8u);
    EXPECT_EQ(bytes.substr(1, 3), "PNG");
    const Image decoded = decodePng(bytes);
    EXPECT_EQ(decoded.width, 17);
    EXPECT_EQ(decoded.height, 9);
    EXPECT_TRUE(decoded.rgba == image.rgba);
    // Row 0 is the top row: the pixel at (0, 1) is the second row's first.
    EXPECT_EQ(decoded.pixel(0, 1)[1], 11);
}

TEST(PngCodec, SameImageSameBytes) {
    EXPECT_EQ(encodePng(gradient(8, 8)), encodePng(gradient(8, 8)));
}

TEST(PngCodec, BadBytesAreAnError) {
    EXPECT_THROW(decodePng("not a png"), std::runtime_error);
    EXPECT_THROW(decodePng(""), std::runtime_error);
}

}  // namespace
}  // namespace substep::render
