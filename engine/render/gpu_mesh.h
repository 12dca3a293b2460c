#pragma once
/// A mesh on the GPU with its own per-instance buffer (model matrix + colour), so every shape
/// that shares it is one instanced draw call.

#include "render/gl_api.h"
#include "render/mesh_data.h"
#include "render/render_math.h"

#include <vector>

namespace substep::render {

/// Per-instance attributes, as mesh.vert and shadow.vert read them.
struct InstanceData {
    float model[16];  ///< column-major
    float colour[4];
};

class GpuMesh {
  public:
    GpuMesh(const GlApi& gl, const MeshData& mesh);
    ~GpuMesh();
    GpuMesh(const GpuMesh&) = delete;
    GpuMesh& operator=(const GpuMesh&) = delete;

    /// Replaces the instance data for the next draws.
    void setInstances(const std::vector<InstanceData>& instances);
    /// Draws every instance with the program in use.
    void draw() const;
    /// Largest distance of a vertex from the mesh origin (for scene bounds).
    float boundingRadius() const { return boundingRadius_; }
    /// Triangles of one instance, and instances set.
    long long triangleCount() const { return indexCount_ / 3; }
    long long instanceCount() const { return instanceCount_; }

  private:
    const GlApi& gl_;
    GLuint vertexArray_ = 0;
    GLuint vertexBuffer_ = 0;
    GLuint indexBuffer_ = 0;
    GLuint instanceBuffer_ = 0;
    GLsizei indexCount_ = 0;
    GLsizei instanceCount_ = 0;
    float boundingRadius_ = 0.0f;
};

}  // namespace substep::render
