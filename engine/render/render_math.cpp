#include "render/render_math.h"

#include <cmath>

namespace substep::render {

Mat4f lookAt(const Vec3f& eye, const Vec3f& target, const Vec3f& up) {
    const Vec3f forward = (target - eye).normalized();
    // A view straight along `up` has no defined roll: borrow another axis.
    Vec3f side = forward.cross(up);
    if (side.squaredNorm() < 1e-12f) side = forward.cross(Vec3f::UnitZ());
    side.normalize();
    const Vec3f trueUp = side.cross(forward);
    Mat4f view = Mat4f::Identity();
    view.block<1, 3>(0, 0) = side.transpose();
    view.block<1, 3>(1, 0) = trueUp.transpose();
    view.block<1, 3>(2, 0) = -forward.transpose();
    view(0, 3) = -side.dot(eye);
    view(1, 3) = -trueUp.dot(eye);
    view(2, 3) = forward.dot(eye);
    return view;
}

Mat4f perspective(float fovY, float aspect, float nearPlane, float farPlane) {
    const float f = 1.0f / std::tan(fovY / 2.0f);
    Mat4f projection = Mat4f::Zero();
    projection(0, 0) = f / aspect;
    projection(1, 1) = f;
    projection(2, 2) = (farPlane + nearPlane) / (nearPlane - farPlane);
    projection(2, 3) = 2.0f * farPlane * nearPlane / (nearPlane - farPlane);
    projection(3, 2) = -1.0f;
    return projection;
}

Mat4f orthographic(float left, float right, float bottom, float top, float nearPlane, float farPlane) {
    Mat4f projection = Mat4f::Identity();
    projection(0, 0) = 2.0f / (right - left);
    projection(1, 1) = 2.0f / (top - bottom);
    projection(2, 2) = -2.0f / (farPlane - nearPlane);
    projection(0, 3) = -(right + left) / (right - left);
    projection(1, 3) = -(top + bottom) / (top - bottom);
    projection(2, 3) = -(farPlane + nearPlane) / (farPlane - nearPlane);
    return projection;
}

Mat4f modelMatrix(const Vec3f& position, const Quatf& orientation, const Vec3f& scale) {
    Mat4f model = Mat4f::Identity();
    model.block<3, 3>(0, 0) = orientation.normalized().toRotationMatrix() * scale.asDiagonal();
    model.block<3, 1>(0, 3) = position;
    return model;
}

}  // namespace substep::render
