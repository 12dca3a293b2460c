#include "render/gpu_mesh.h"

#include <algorithm>
#include <cstddef>

namespace substep::render {

GpuMesh::GpuMesh(const GlApi& gl, const MeshData& mesh) : gl_(gl) {
    for (const MeshVertex& vertex : mesh.vertices) {
        boundingRadius_ = std::max(boundingRadius_, Vec3f(vertex.position[0], vertex.position[1],
                                                          vertex.position[2]).norm());
    }
    indexCount_ = static_cast<GLsizei>(mesh.indices.size());

    gl_.GenVertexArrays(1, &vertexArray_);
    gl_.BindVertexArray(vertexArray_);

    gl_.GenBuffers(1, &vertexBuffer_);
    gl_.BindBuffer(GL_ARRAY_BUFFER, vertexBuffer_);
    gl_.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(mesh.vertices.size() * sizeof(MeshVertex)),
                   mesh.vertices.data(), GL_STATIC_DRAW);
    gl_.EnableVertexAttribArray(0);
    gl_.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(MeshVertex),
                            reinterpret_cast<const void*>(offsetof(MeshVertex, position)));
    gl_.EnableVertexAttribArray(1);
    gl_.VertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(MeshVertex),
                            reinterpret_cast<const void*>(offsetof(MeshVertex, normal)));

    gl_.GenBuffers(1, &indexBuffer_);
    gl_.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, indexBuffer_);
    gl_.BufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(mesh.indices.size() * sizeof(uint32_t)),
                   mesh.indices.data(), GL_STATIC_DRAW);

    // Instance attributes: the model matrix takes four vec4 locations (2-5), the colour one (6).
    gl_.GenBuffers(1, &instanceBuffer_);
    gl_.BindBuffer(GL_ARRAY_BUFFER, instanceBuffer_);
    for (GLuint column = 0; column < 4; ++column) {
        gl_.EnableVertexAttribArray(2 + column);
        gl_.VertexAttribPointer(2 + column, 4, GL_FLOAT, GL_FALSE, sizeof(InstanceData),
                                reinterpret_cast<const void*>(offsetof(InstanceData, model) +
                                                              column * 4 * sizeof(float)));
        gl_.VertexAttribDivisor(2 + column, 1);
    }
    gl_.EnableVertexAttribArray(6);
    gl_.VertexAttribPointer(6, 4, GL_FLOAT, GL_FALSE, sizeof(InstanceData),
                            reinterpret_cast<const void*>(offsetof(InstanceData, colour)));
    gl_.VertexAttribDivisor(6, 1);

    gl_.BindVertexArray(0);
}

GpuMesh::~GpuMesh() {
    gl_.DeleteVertexArrays(1, &vertexArray_);
    gl_.DeleteBuffers(1, &vertexBuffer_);
    gl_.DeleteBuffers(1, &indexBuffer_);
    gl_.DeleteBuffers(1, &instanceBuffer_);
}

void GpuMesh::setInstances(const std::vector<InstanceData>& instances) {
    instanceCount_ = static_cast<GLsizei>(instances.size());
    gl_.BindBuffer(GL_ARRAY_BUFFER, instanceBuffer_);
    gl_.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(instances.size() * sizeof(InstanceData)),
                   instances.data(), GL_STREAM_DRAW);
}

void GpuMesh::draw() const {
    if (instanceCount_ == 0 || indexCount_ == 0) return;
    gl_.BindVertexArray(vertexArray_);
    gl_.DrawElementsInstanced(GL_TRIANGLES, indexCount_, GL_UNSIGNED_INT, nullptr, instanceCount_);
    gl_.BindVertexArray(0);
}

}  // namespace substep::render
