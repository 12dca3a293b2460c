#pragma once
/// The float types the renderer works in (GPU precision; the physics stays double) and the
/// usual camera matrices, column-major like GL.

#include <Eigen/Geometry>

namespace substep::render {

using Vec2f = Eigen::Vector2f;
using Vec3f = Eigen::Vector3f;
using Vec4f = Eigen::Vector4f;
using Quatf = Eigen::Quaternionf;
using Mat3f = Eigen::Matrix3f;
using Mat4f = Eigen::Matrix4f;

/// View matrix of an eye at `eye` looking at `target`; `up` need not be orthogonal to the view.
Mat4f lookAt(const Vec3f& eye, const Vec3f& target, const Vec3f& up);
/// Right-handed perspective projection to GL clip space; fovY in radians.
Mat4f perspective(float fovY, float aspect, float nearPlane, float farPlane);
/// Orthographic projection of the box [left, right] x [bottom, top] x [-near, -far] (view space).
Mat4f orthographic(float left, float right, float bottom, float top, float nearPlane, float farPlane);
/// Translation * rotation * scale.
Mat4f modelMatrix(const Vec3f& position, const Quatf& orientation, const Vec3f& scale);

}  // namespace substep::render
