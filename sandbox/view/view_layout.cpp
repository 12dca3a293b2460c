#include "view/view_layout.h"

#include <algorithm>
#include <cmath>

namespace substep::view {

ViewArea viewArea(float displayWidth, float displayHeight, bool panelShown, float panelWidth) {
    const float width = std::max(displayWidth, 1.0f);
    const float height = std::max(displayHeight, 1.0f);
    const float panel = panelShown ? std::clamp(panelWidth, 0.0f, std::floor(width / 2.0f)) : 0.0f;
    return {.left = panel, .top = 0.0f, .width = std::max(width - panel, 1.0f), .height = height};
}

render::RenderTarget pixelArea(const ViewArea& area, render::PixelSize framebuffer, float displayWidth,
                               float displayHeight) {
    const float scaleX = static_cast<float>(framebuffer.width) / std::max(displayWidth, 1.0f);
    const float scaleY = static_cast<float>(framebuffer.height) / std::max(displayHeight, 1.0f);
    const int left = std::clamp(static_cast<int>(std::lround(area.left * scaleX)), 0, framebuffer.width);
    const int right = std::clamp(static_cast<int>(std::lround((area.left + area.width) * scaleX)), left, framebuffer.width);
    const int top = std::clamp(static_cast<int>(std::lround(area.top * scaleY)), 0, framebuffer.height);
    const int bottom =
        std::clamp(static_cast<int>(std::lround((area.top + area.height) * scaleY)), top, framebuffer.height);
    return {.framebuffer = 0,
            .size = {std::max(right - left, 1), std::max(bottom - top, 1)},
            .originX = left,
            .originY = framebuffer.height - bottom};
}

}  // namespace substep::view
