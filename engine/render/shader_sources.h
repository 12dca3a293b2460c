#pragma once
/// The GLSL files of shaders/, compiled into the program (embed_shaders.cmake generates the
/// definition), so rendering works from any working directory.

#include <string_view>

namespace substep::render {

/// The text of shaders/NAME (e.g. "mesh.vert"). Throws std::runtime_error for an unknown name.
std::string_view shaderSource(std::string_view name);

}  // namespace substep::render
