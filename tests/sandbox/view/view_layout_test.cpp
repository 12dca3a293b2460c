// sandbox/view/view_layout.cpp: the view beside the docked panel, never under it, and its pixels.

#include "view/view_layout.h"

#include <gtest/gtest.h>

namespace substep::view {
namespace {

TEST(ViewLayoutTest, TheViewStartsWhereThePanelEnds) {
    const ViewArea area = viewArea(1400.0f, 800.0f, true, 380.0f);
    EXPECT_FLOAT_EQ(area.left, 380.0f);
    EXPECT_FLOAT_EQ(area.width, 1020.0f);
    EXPECT_FLOAT_EQ(area.top, 0.0f);
    EXPECT_FLOAT_EQ(area.height, 800.0f);
}

TEST(ViewLayoutTest, HiddenUiGivesTheWholeWindow) {
    const ViewArea area = viewArea(1400.0f, 800.0f, false, 380.0f);
    EXPECT_FLOAT_EQ(area.left, 0.0f);
    EXPECT_FLOAT_EQ(area.width, 1400.0f);
}

TEST(ViewLayoutTest, ANarrowWindowKeepsHalfForTheView) {
    const ViewArea area = viewArea(500.0f, 400.0f, true, 380.0f);
    EXPECT_FLOAT_EQ(area.left, 250.0f);
    EXPECT_FLOAT_EQ(area.width, 250.0f);
    // Degenerate sizes (a minimised window) stay positive and finite.
    const ViewArea none = viewArea(0.0f, 0.0f, true, 380.0f);
    EXPECT_GT(none.width, 0.0f);
    EXPECT_GT(none.height, 0.0f);
}

TEST(ViewLayoutTest, PixelsOfTheViewWithGlOriginAtTheBottom) {
    const ViewArea area = viewArea(1400.0f, 800.0f, true, 380.0f);
    const render::RenderTarget pixels = pixelArea(area, {1400, 800}, 1400.0f, 800.0f);
    EXPECT_EQ(pixels.originX, 380);
    EXPECT_EQ(pixels.originY, 0);
    EXPECT_EQ(pixels.size, (render::PixelSize{1020, 800}));
    // A HiDPI framebuffer has twice the pixels of the window's units; a half-size buffer half.
    const render::RenderTarget doubled = pixelArea(area, {2800, 1600}, 1400.0f, 800.0f);
    EXPECT_EQ(doubled.originX, 760);
    EXPECT_EQ(doubled.size, (render::PixelSize{2040, 1600}));
    const render::RenderTarget half = pixelArea(area, {700, 400}, 1400.0f, 800.0f);
    EXPECT_EQ(half.originX, 190);
    EXPECT_EQ(half.size, (render::PixelSize{510, 400}));
    // An area below the top edge: GL counts rows from the bottom.
    const render::RenderTarget lower = pixelArea({.left = 0.0f, .top = 100.0f, .width = 200.0f, .height = 300.0f},
                                                 {1400, 800}, 1400.0f, 800.0f);
    EXPECT_EQ(lower.originY, 400);
    EXPECT_EQ(lower.size.height, 300);
}

}  // namespace
}  // namespace substep::view
