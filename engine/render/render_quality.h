#pragma once
/// Quality levels of the interactive renderer: how many samples smooth the edges, how large and
/// how filtered the sun's shadow map is, and how finely spheres are tessellated. A software
/// rasteriser (Mesa's llvmpipe or softpipe: a VM, a CI machine, a laptop without a driver)
/// spends its time per pixel and per triangle, so it gets the light level; a GPU the full one,
/// which is what headless renders always use.

#include <string>
#include <string_view>

namespace substep::render {

enum class QualityLevel { Light, Medium, Full };

/// How the sun's shadow is drawn.
enum class ShadowMode {
    Off,   ///< no shadow pass; everything the sun faces is lit
    Hard,  ///< one bilinear tap of the shadow map per pixel
    Soft,  ///< a 4 x 4 percentage-closer filter (headless renders)
};

/// What a quality level sets.
struct RenderQuality {
    int msaaSamples = 4;      ///< samples per pixel of the scene (0: none)
    /// The scene is drawn at this fraction of the view's pixels per side and scaled up
    /// (bilinear) into it: a software rasteriser's cost is mostly per pixel.
    float renderScale = 1.0f;
    ShadowMode shadows = ShadowMode::Soft;
    int shadowMapSize = 2048; ///< texels per side
    int sphereRings = 24;     ///< latitude bands of the unit sphere
    int sphereSegments = 48;  ///< longitude slices of the unit sphere
    /// Spheres smaller on screen than this radius (pixels) get a coarse 6 x 12 mesh; 0 never.
    float coarseSphereBelowPixels = 0.0f;
    bool frontToBack = false;  ///< instances drawn nearest first (early depth rejection)
    friend bool operator==(const RenderQuality&, const RenderQuality&) = default;
};

/// The settings of `level`. Full is what headless renders use.
RenderQuality qualitySettings(QualityLevel level);

/// The level for a context whose GL_RENDERER string is `glRenderer`: Light for a software
/// rasteriser (llvmpipe, softpipe, swrast, "Software Rasterizer"), Full otherwise.
QualityLevel qualityForRenderer(std::string_view glRenderer);

/// "light", "medium", "full".
const char* qualityName(QualityLevel level);
/// The level named `name` (as qualityName writes it); false when there is none.
bool parseQualityLevel(std::string_view name, QualityLevel& level);

}  // namespace substep::render
