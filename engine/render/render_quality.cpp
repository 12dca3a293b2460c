#include "render/render_quality.h"

#include <algorithm>
#include <array>
#include <cctype>

namespace substep::render {

RenderQuality qualitySettings(QualityLevel level) {
    switch (level) {
        // Measured under Xvfb with llvmpipe at 1400x800 (docs/PERFORMANCE_LOG.md): its time grows
        // with the pixels drawn (multisampling, the 16-tap shadow filter, full resolution) and,
        // on spheres1000, with the 2304-triangle sphere (2.3 million triangles drawn twice,
        // shadow and view).
        case QualityLevel::Light:
            return {.msaaSamples = 0, .renderScale = 0.5f, .shadows = ShadowMode::Hard, .shadowMapSize = 512,
                    .sphereRings = 12, .sphereSegments = 24, .coarseSphereBelowPixels = 16.0f, .frontToBack = true};
        case QualityLevel::Medium:
            return {.msaaSamples = 2, .shadows = ShadowMode::Soft, .shadowMapSize = 1024, .sphereRings = 16,
                    .sphereSegments = 32, .coarseSphereBelowPixels = 8.0f, .frontToBack = true};
        case QualityLevel::Full: return {};
    }
    return {};
}

QualityLevel qualityForRenderer(std::string_view glRenderer) {
    std::string lower(glRenderer);
    std::transform(lower.begin(), lower.end(), lower.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    constexpr std::array<std::string_view, 4> kSoftware{"llvmpipe", "softpipe", "swrast", "software rasterizer"};
    for (const std::string_view name : kSoftware) {
        if (lower.find(name) != std::string::npos) return QualityLevel::Light;
    }
    return QualityLevel::Full;
}

const char* qualityName(QualityLevel level) {
    switch (level) {
        case QualityLevel::Light: return "light";
        case QualityLevel::Medium: return "medium";
        case QualityLevel::Full: return "full";
    }
    return "full";
}

bool parseQualityLevel(std::string_view name, QualityLevel& level) {
    for (const QualityLevel each : {QualityLevel::Light, QualityLevel::Medium, QualityLevel::Full}) {
        if (name == qualityName(each)) {
            level = each;
            return true;
        }
    }
    return false;
}

}  // namespace substep::render
