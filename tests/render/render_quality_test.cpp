// engine/render/render_quality.cpp: software rasterisers get the light level, GPUs the full one
// (what headless renders use), and each level is cheaper than the one above it.

#include "render/render_quality.h"
#include "render/renderer.h"

#include <gtest/gtest.h>

namespace substep::render {
namespace {

TEST(RenderQualityTest, SoftwareRasterisersGetTheLightLevel) {
    EXPECT_EQ(qualityForRenderer("llvmpipe (LLVM 15.0.6, 256 bits)"), QualityLevel::Light);
    EXPECT_EQ(qualityForRenderer("softpipe"), QualityLevel::Light);
    EXPECT_EQ(qualityForRenderer("Mesa OffScreen (swrast)"), QualityLevel::Light);
    EXPECT_EQ(qualityForRenderer("Software Rasterizer"), QualityLevel::Light);
    EXPECT_EQ(qualityForRenderer("LLVMPIPE"), QualityLevel::Light);
    EXPECT_EQ(qualityForRenderer("NVIDIA GeForce RTX 3060/PCIe/SSE2"), QualityLevel::Full);
    EXPECT_EQ(qualityForRenderer("AMD Radeon RX 6600 (navi23, LLVM 15.0.6, DRM 3.49)"), QualityLevel::Full);
    EXPECT_EQ(qualityForRenderer("Mesa Intel(R) UHD Graphics 620 (KBL GT2)"), QualityLevel::Full);
    EXPECT_EQ(qualityForRenderer(""), QualityLevel::Full);
}

TEST(RenderQualityTest, FullIsWhatHeadlessRendersDraw) {
    // Headless renders construct the renderer with default settings; the full level must be
    // exactly those, so the window at full quality draws what `render` draws.
    EXPECT_EQ(rendererSettings(qualitySettings(QualityLevel::Full)), RendererSettings{});
    EXPECT_EQ(qualitySettings(QualityLevel::Full).msaaSamples, 4);
    EXPECT_FLOAT_EQ(qualitySettings(QualityLevel::Full).renderScale, 1.0f);
}

TEST(RenderQualityTest, EachLevelCostsLessThanTheOneAbove) {
    const RenderQuality light = qualitySettings(QualityLevel::Light);
    const RenderQuality medium = qualitySettings(QualityLevel::Medium);
    const RenderQuality full = qualitySettings(QualityLevel::Full);
    const auto pixels = [](const RenderQuality& q) {
        return q.renderScale * q.renderScale * static_cast<float>(std::max(q.msaaSamples, 1));
    };
    EXPECT_LT(pixels(light), pixels(medium));
    EXPECT_LT(pixels(medium), pixels(full));
    EXPECT_LE(light.shadowMapSize, medium.shadowMapSize);
    EXPECT_LE(medium.shadowMapSize, full.shadowMapSize);
    EXPECT_LT(light.sphereRings * light.sphereSegments, full.sphereRings * full.sphereSegments);
    EXPECT_NE(light.shadows, ShadowMode::Soft);  // one tap instead of sixteen
}

TEST(RenderQualityTest, NamesReadBack) {
    for (const QualityLevel level : {QualityLevel::Light, QualityLevel::Medium, QualityLevel::Full}) {
        QualityLevel parsed = QualityLevel::Full;
        ASSERT_TRUE(parseQualityLevel(qualityName(level), parsed));
        EXPECT_EQ(parsed, level);
    }
    QualityLevel untouched = QualityLevel::Medium;
    EXPECT_FALSE(parseQualityLevel("ultra", untouched));
    EXPECT_FALSE(parseQualityLevel("", untouched));
    EXPECT_EQ(untouched, QualityLevel::Medium);
}

}  // namespace
}  // namespace substep::render
