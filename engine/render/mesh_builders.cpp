#include "render/mesh_builders.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace substep::render {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

uint32_t addVertex(MeshData& mesh, const Vec3f& position, const Vec3f& normal) {
    mesh.vertices.push_back({{position.x(), position.y(), position.z()},
                             {normal.x(), normal.y(), normal.z()}});
    return static_cast<uint32_t>(mesh.vertices.size() - 1);
}

void addQuad(MeshData& mesh, uint32_t a, uint32_t b, uint32_t c, uint32_t d) {
    mesh.indices.insert(mesh.indices.end(), {a, b, c, a, c, d});
}

/// Rows of vertices on a surface of revolution about y, joined into quads. Each ring is a
/// (radius, y, normal angle) triple; the seam vertex is duplicated so rings close.
void revolve(MeshData& mesh, const std::vector<Vec3f>& rings, int segments) {
    const uint32_t first = static_cast<uint32_t>(mesh.vertices.size());
    for (const Vec3f& ring : rings) {
        const float radius = ring.x();
        const float y = ring.y();
        const float normalAngle = ring.z();  // angle of the normal above the horizontal
        for (int s = 0; s <= segments; ++s) {
            const float phi = 2.0f * kPi * static_cast<float>(s) / static_cast<float>(segments);
            const Vec3f around(std::cos(phi), 0.0f, -std::sin(phi));
            const Vec3f normal = around * std::cos(normalAngle) + Vec3f::UnitY() * std::sin(normalAngle);
            addVertex(mesh, around * radius + Vec3f(0.0f, y, 0.0f), normal);
        }
    }
    const uint32_t stride = static_cast<uint32_t>(segments + 1);
    for (uint32_t r = 0; r + 1 < rings.size(); ++r) {
        for (uint32_t s = 0; s < static_cast<uint32_t>(segments); ++s) {
            const uint32_t top = first + r * stride + s;
            const uint32_t bottom = top + stride;
            // Rings run from the top down; this order is counter-clockwise from outside.
            addQuad(mesh, top, bottom, bottom + 1, top + 1);
        }
    }
}

}  // namespace

MeshData unitSphereMesh(int rings, int segments) {
    std::vector<Vec3f> profile;
    for (int r = 0; r <= rings; ++r) {
        const float theta = kPi / 2.0f - kPi * static_cast<float>(r) / static_cast<float>(rings);
        profile.emplace_back(std::cos(theta), std::sin(theta), theta);
    }
    MeshData mesh;
    revolve(mesh, profile, segments);
    return mesh;
}

MeshData unitBoxMesh() {
    MeshData mesh;
    for (int axis = 0; axis < 3; ++axis) {
        for (const float sign : {1.0f, -1.0f}) {
            Vec3f normal = Vec3f::Zero();
            normal[axis] = sign;
            const Vec3f u = Vec3f::Unit((axis + 1) % 3) * sign;
            const Vec3f v = Vec3f::Unit((axis + 2) % 3);
            const Vec3f centre = normal * 0.5f;
            const uint32_t a = addVertex(mesh, centre - 0.5f * u - 0.5f * v, normal);
            const uint32_t b = addVertex(mesh, centre + 0.5f * u - 0.5f * v, normal);
            const uint32_t c = addVertex(mesh, centre + 0.5f * u + 0.5f * v, normal);
            const uint32_t d = addVertex(mesh, centre - 0.5f * u + 0.5f * v, normal);
            addQuad(mesh, a, b, c, d);
        }
    }
    return mesh;
}

MeshData capsuleMesh(float radius, float length, int rings, int segments) {
    // Top hemisphere, then the bottom one shifted down: the band between them is the cylinder.
    std::vector<Vec3f> profile;
    const float half = length / 2.0f;
    for (int r = 0; r <= rings; ++r) {
        const float theta = kPi / 2.0f - kPi / 2.0f * static_cast<float>(r) / static_cast<float>(rings);
        profile.emplace_back(radius * std::cos(theta), half + radius * std::sin(theta), theta);
    }
    for (int r = 0; r <= rings; ++r) {
        const float theta = -kPi / 2.0f * static_cast<float>(r) / static_cast<float>(rings);
        profile.emplace_back(radius * std::cos(theta), -half + radius * std::sin(theta), theta);
    }
    MeshData mesh;
    revolve(mesh, profile, segments);
    return mesh;
}

MeshData unitCylinderMesh(int segments) {
    MeshData mesh;
    // The side: two rings with horizontal normals (the revolve's normal angle 0).
    revolve(mesh, {Vec3f(1.0f, 0.5f, 0.0f), Vec3f(1.0f, -0.5f, 0.0f)}, segments);
    // Each face a fan around its centre, with its own vertices so the rim edge stays sharp.
    for (const float side : {1.0f, -1.0f}) {
        const Vec3f normal(0.0f, side, 0.0f);
        const uint32_t centre = addVertex(mesh, Vec3f(0.0f, 0.5f * side, 0.0f), normal);
        for (int s = 0; s < segments; ++s) {
            const float phi = 2.0f * kPi * static_cast<float>(s) / static_cast<float>(segments);
            addVertex(mesh, Vec3f(std::cos(phi), 0.5f * side, -std::sin(phi)), normal);
        }
        for (int s = 0; s < segments; ++s) {
            const uint32_t a = centre + 1 + static_cast<uint32_t>(s);
            const uint32_t b = centre + 1 + static_cast<uint32_t>((s + 1) % segments);
            // Counter-clockwise seen from outside: phi grows counter-clockwise seen from +y.
            if (side > 0.0f) mesh.indices.insert(mesh.indices.end(), {centre, a, b});
            else mesh.indices.insert(mesh.indices.end(), {centre, b, a});
        }
    }
    return mesh;
}

MeshData flatShadedMesh(std::span<const Vec3f> points, std::span<const uint32_t> triangles) {
    MeshData mesh;
    for (std::size_t t = 0; t + 2 < triangles.size(); t += 3) {
        const Vec3f& a = points[triangles[t]];
        const Vec3f& b = points[triangles[t + 1]];
        const Vec3f& c = points[triangles[t + 2]];
        const Vec3f normal = (b - a).cross(c - a).normalized();
        mesh.indices.push_back(addVertex(mesh, a, normal));
        mesh.indices.push_back(addVertex(mesh, b, normal));
        mesh.indices.push_back(addVertex(mesh, c, normal));
    }
    return mesh;
}

MeshData heightfieldMesh(int columns, int rows, Vec2f corner, Vec2f spacing, std::span<const float> heights) {
    MeshData mesh;
    if (columns < 2 || rows < 2 || heights.size() < static_cast<std::size_t>(columns * rows)) return mesh;
    const auto height = [&](int column, int row) {
        column = std::clamp(column, 0, columns - 1);
        row = std::clamp(row, 0, rows - 1);
        return heights[static_cast<std::size_t>(row * columns + column)];
    };
    for (int row = 0; row < rows; ++row) {
        for (int column = 0; column < columns; ++column) {
            // Central differences give smooth normals across the grid.
            const float dx = (height(column + 1, row) - height(column - 1, row)) / (2.0f * spacing.x());
            const float dz = (height(column, row + 1) - height(column, row - 1)) / (2.0f * spacing.y());
            addVertex(mesh,
                      Vec3f(corner.x() + static_cast<float>(column) * spacing.x(), height(column, row),
                            corner.y() + static_cast<float>(row) * spacing.y()),
                      Vec3f(-dx, 1.0f, -dz).normalized());
        }
    }
    for (int row = 0; row + 1 < rows; ++row) {
        for (int column = 0; column + 1 < columns; ++column) {
            const auto index = [&](int c, int r) { return static_cast<uint32_t>(r * columns + c); };
            // Seen from above (+y), with z growing toward the viewer: counter-clockwise.
            addQuad(mesh, index(column, row), index(column, row + 1), index(column + 1, row + 1),
                    index(column + 1, row));
        }
    }
    return mesh;
}

MeshData tubeMesh(std::span<const Vec3f> centres, float radius, bool closed, int segments) {
    MeshData mesh;
    const std::size_t count = centres.size();
    if (count < 2) return mesh;
    const auto tangentAt = [&](std::size_t i) {
        const std::size_t next = closed ? (i + 1) % count : std::min(i + 1, count - 1);
        const std::size_t previous = closed ? (i + count - 1) % count : (i == 0 ? 0 : i - 1);
        return (centres[next] - centres[previous]).normalized();
    };
    // Parallel transport: rotate the previous normal by the turn of the tangent.
    Vec3f tangent = tangentAt(0);
    Vec3f normal = tangent.unitOrthogonal();
    const std::size_t ringCount = closed ? count + 1 : count;
    const uint32_t stride = static_cast<uint32_t>(segments + 1);
    for (std::size_t i = 0; i < ringCount; ++i) {
        const Vec3f nextTangent = tangentAt(i % count);
        normal = Quatf::FromTwoVectors(tangent, nextTangent) * normal;
        normal = (normal - nextTangent * nextTangent.dot(normal)).normalized();
        tangent = nextTangent;
        const Vec3f binormal = tangent.cross(normal);
        for (int s = 0; s <= segments; ++s) {
            const float phi = 2.0f * kPi * static_cast<float>(s) / static_cast<float>(segments);
            const Vec3f direction = normal * std::cos(phi) + binormal * std::sin(phi);
            addVertex(mesh, centres[i % count] + radius * direction, direction);
        }
    }
    for (uint32_t r = 0; r + 1 < ringCount; ++r) {
        for (uint32_t s = 0; s < static_cast<uint32_t>(segments); ++s) {
            const uint32_t a = r * stride + s;
            addQuad(mesh, a, a + 1, a + stride + 1, a + stride);
        }
    }
    if (!closed) {
        // Flat caps at both ends.
        for (const bool atEnd : {false, true}) {
            const std::size_t i = atEnd ? count - 1 : 0;
            const Vec3f capNormal = atEnd ? tangentAt(i) : Vec3f(-tangentAt(i));
            const uint32_t ringStart = static_cast<uint32_t>(i) * stride;
            const uint32_t centre = addVertex(mesh, centres[i], capNormal);
            const uint32_t first = static_cast<uint32_t>(mesh.vertices.size());
            for (int s = 0; s <= segments; ++s) {
                const MeshVertex& v = mesh.vertices[ringStart + static_cast<uint32_t>(s)];
                addVertex(mesh, Vec3f(v.position[0], v.position[1], v.position[2]), capNormal);
            }
            for (uint32_t s = 0; s < static_cast<uint32_t>(segments); ++s) {
                if (atEnd)
                    mesh.indices.insert(mesh.indices.end(), {centre, first + s, first + s + 1});
                else
                    mesh.indices.insert(mesh.indices.end(), {centre, first + s + 1, first + s});
            }
        }
    }
    return mesh;
}

}  // namespace substep::render
