#pragma once
/// A camera that shows a sphere of content whole: for scenes that name no camera, and for a
/// viewer's "frame all".

#include "render/render_scene.h"

namespace substep::render {

/// Looks at `centre` from the front and a little above (the scene's +z side, 20° up), far enough
/// that a sphere of `radius` fits the vertical and horizontal field of view.
Camera framingCamera(const Vec3f& centre, float radius, float fovY, float aspect);

}  // namespace substep::render
