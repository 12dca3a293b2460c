#pragma once
/// Triangle meshes on the CPU side, as the renderer uploads them: positions and normals per
/// vertex, counter-clockwise triangles seen from outside.

#include "render/render_math.h"

#include <cstdint>
#include <vector>

namespace substep::render {

struct MeshVertex {
    float position[3];
    float normal[3];
};

struct MeshData {
    std::vector<MeshVertex> vertices;
    std::vector<uint32_t> indices;  ///< three per triangle
};

}  // namespace substep::render
