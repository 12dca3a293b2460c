#pragma once
/// The panel's and the keys' switches of the bodies' debug layers (physics/debug_draw.h):
/// broadphase boxes, centres of mass, velocities, and the scale of every arrow (forces, torques,
/// velocities). The joint and contact layers keep their checkboxes in view_panel.cpp.

#include "scene_drawing.h"
#include "view/view_controls.h"

namespace substep::view {

/// Checkboxes of the bodies' layers and the arrow-scale slider; true when one changed.
bool drawBodyLayerControls(DrawingOptions& drawing);

/// Applies the frame's B, M and V presses (each toggles its layer; two in a frame cancel);
/// true when a layer changed.
bool toggleLayersByKey(const KeyActions& keys, DrawingOptions& drawing);

}  // namespace substep::view
