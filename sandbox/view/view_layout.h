#pragma once
/// Where the 3D view goes: the panel is docked at the window's left edge, full height, and the
/// view fills the rest, so nothing of the scene hides behind the panel. With the UI hidden (Tab)
/// the view takes the whole window. Coordinates are ImGui's (screen units, y down).

#include "render/render_target.h"

namespace substep::view {

/// The panel's width in screen units while it is shown.
inline constexpr float kPanelWidth = 380.0f;

/// The part of the window the runs are drawn in.
struct ViewArea {
    float left = 0.0f;
    float top = 0.0f;
    float width = 1.0f;
    float height = 1.0f;
};

/// The view beside a docked panel `panelWidth` wide in a window `displayWidth` x `displayHeight`
/// (the panel takes at most half a narrow window), or the whole window with the panel hidden.
ViewArea viewArea(float displayWidth, float displayHeight, bool panelShown, float panelWidth = kPanelWidth);

/// The pixels of `area` in a framebuffer of `framebuffer` pixels whose window is `displayWidth`
/// screen units wide (a HiDPI framebuffer has more pixels than units): GL's origin at the bottom.
render::RenderTarget pixelArea(const ViewArea& area, render::PixelSize framebuffer, float displayWidth,
                               float displayHeight);

}  // namespace substep::view
