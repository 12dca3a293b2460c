// Tests sandbox/capture/image_diff.cpp: pixels differing by more than a tolerance, and the heat
// map.

#include "capture/image_diff.h"

#include <gtest/gtest.h>

namespace substep::capture {
namespace {

render::Image grey(int width, int height, uint8_t level) {
    render::Image image{.width = width, .height = height};
    image.rgba.assign(static_cast<std::size_t>(width) * height * 4, level);
    return image;
}

void setChannel(render::Image& image, int x, int y, int channel, uint8_t value) {
    image.rgba[(static_cast<std::size_t>(y) * image.width + x) * 4 + channel] = value;
}

TEST(ImageDiff, CountsPixelsWithAChannelOffByMoreThanTheTolerance) {
    const render::Image golden = grey(4, 5, 100);
    render::Image fresh = grey(4, 5, 100);
    setChannel(fresh, 0, 0, 0, 108);  // off by 8: within a tolerance of 8
    setChannel(fresh, 3, 4, 2, 91);   // off by 9
    setChannel(fresh, 2, 2, 3, 0);    // alpha off by 100
    const ImageComparison result = compareImages(golden, fresh, 8);
    EXPECT_FALSE(result.sizeDiffers);
    EXPECT_EQ(result.pixels, 20);
    EXPECT_EQ(result.differing, 2);
    EXPECT_DOUBLE_EQ(result.fraction(), 0.1);
    EXPECT_EQ(result.largest, 100);
    EXPECT_EQ(compareImages(golden, fresh, 0).differing, 3);
    EXPECT_EQ(compareImages(golden, golden, 0).differing, 0);
}

TEST(ImageDiff, ADifferentSizeIsReportedAsSuch) {
    const ImageComparison result = compareImages(grey(4, 5, 0), grey(5, 4, 0), 0);
    EXPECT_TRUE(result.sizeDiffers);
    EXPECT_EQ(result.differing, 0);
}

TEST(ImageDiff, HeatMapDimsMatchingPixelsAndColoursDifferingOnes) {
    const render::Image golden = grey(2, 1, 200);
    render::Image fresh = grey(2, 1, 200);
    setChannel(fresh, 1, 0, 1, 0);  // off by 200
    const render::Image map = differenceHeatMap(golden, fresh, 8);
    ASSERT_EQ(map.width, 2);
    const uint8_t* same = map.pixel(0, 0);
    EXPECT_EQ(same[0], 50);
    EXPECT_EQ(same[1], 50);
    EXPECT_EQ(same[2], 50);
    const uint8_t* differing = map.pixel(1, 0);
    EXPECT_EQ(differing[0], 255);  // strongly red, turning yellow
    EXPECT_GT(differing[1], 100);
    EXPECT_EQ(differing[2], 0);
    EXPECT_EQ(differing[3], 255);
}

}  // namespace
}  // namespace substep::capture
