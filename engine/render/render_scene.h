#pragma once
/// What the renderer draws, as plain data: shape instances with a transform and a colour, a
/// ground plane, debug lines, a camera and a sun. Whoever owns the simulation fills one per
/// frame (sandbox/scene_drawing.h does it for a physics World); the renderer knows nothing of
/// the physics (MuJoCo's mjvScene plays the same part).

#include "render/mesh_data.h"
#include "render/render_math.h"

#include <memory>
#include <optional>
#include <vector>

namespace substep::render {

/// Colours are sRGB in [0, 1], as picked; the shaders light them in linear space.
using Colour = Vec3f;

enum class ShapeKind {
    Sphere,   ///< dimensions.x() = radius
    Box,      ///< dimensions = full extents
    Capsule,  ///< dimensions.x() = radius, dimensions.y() = length between cap centres (along y)
    Cylinder, ///< dimensions.x() = radius, dimensions.y() = length between the flat faces (along y)
    Mesh,     ///< `mesh` in the instance's own frame (triangle meshes, heightfields, tubes)
};

struct RenderInstance {
    ShapeKind kind = ShapeKind::Box;
    Vec3f dimensions = Vec3f::Ones();
    /// For ShapeKind::Mesh. Instances sharing one MeshData are drawn in one instanced call, and
    /// the GPU copy is kept while some instance uses it, so keep the pointer stable across frames.
    std::shared_ptr<const MeshData> mesh;
    Vec3f position = Vec3f::Zero();
    Quatf orientation = Quatf::Identity();
    Colour colour = Colour(0.8f, 0.8f, 0.8f);
};

struct DebugLine {
    Vec3f from = Vec3f::Zero();
    Vec3f to = Vec3f::Zero();
    Colour colour = Colour(1.0f, 1.0f, 1.0f);
};

struct Camera {
    Vec3f position = Vec3f(0.0f, 1.5f, 4.0f);
    Vec3f target = Vec3f(0.0f, 0.5f, 0.0f);
    Vec3f up = Vec3f::UnitY();
    float fovY = 0.8f;  ///< vertical field of view (rad)
};

struct Sun {
    Vec3f direction = Vec3f(-0.4f, 0.8f, 0.5f).normalized();  ///< toward the sun
    Colour colour = Colour(1.0f, 0.96f, 0.88f);
    float intensity = 1.7f;
};

/// The plane n·x = offset, drawn as a large square with a grid around the camera's target.
struct Ground {
    Vec3f normal = Vec3f::UnitY();
    float offset = 0.0f;
    Colour colour = Colour(0.66f, 0.66f, 0.64f);
    float gridSpacing = 1.0f;  ///< major grid lines (m); minor lines at a tenth of it
};

struct Sky {
    Colour zenith = Colour(0.36f, 0.55f, 0.80f);
    Colour horizon = Colour(0.80f, 0.86f, 0.92f);
};

struct RenderScene {
    Camera camera;
    Sun sun;
    Sky sky;
    std::optional<Ground> ground;
    std::vector<RenderInstance> instances;
    std::vector<DebugLine> lines;
};

}  // namespace substep::render
