#pragma once
/// Screenshots of the window: its back buffer read as drawn (the whole window, or the 3D view's
/// area alone), and the P key's files, named after the scene and frame in the working folder
/// and never written over.

#include "render/gl_api.h"
#include "render/image.h"
#include "render/render_target.h"

#include <filesystem>
#include <string>

namespace substep::view {

/// The pixels of `area` of the default framebuffer's back buffer, top row first, opaque.
/// Throws std::runtime_error on a GL error.
render::Image readBackBuffer(const render::GlApi& gl, const render::RenderTarget& area);

/// `folder/substep_SCENE_fFRAME.png`, with `_2`, `_3`, ... before `.png` when that exists;
/// SCENE is the scene's label without folders or `.json`, kept to letters, digits, `_` and `-`.
std::filesystem::path screenshotPath(const std::filesystem::path& folder, const std::string& sceneLabel,
                                     long long frame);

/// Writes `image` as a PNG to `path` whole or not at all (atomic_file.h). Throws OutputError.
void saveScreenshot(const render::Image& image, const std::filesystem::path& path);

}  // namespace substep::view
