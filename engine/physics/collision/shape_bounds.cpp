#include "physics/collision/shape_bounds.h"

#include <cmath>
#include <limits>

namespace substep {

namespace {

Aabb infiniteBox() {
    const double inf = std::numeric_limits<double>::infinity();
    return {Vec3::Constant(-inf), Vec3::Constant(inf)};
}

Aabb centredBox(const Vec3& halfExtents) {
    return {-halfExtents, halfExtents};
}

}  // namespace

Aabb transformedBounds(const Aabb& local, const Vec3& position, const Mat3& rotation) {
    if (local.isEmpty()) return {};
    const Vec3 centre = position + rotation * local.center();
    const Vec3 half = rotation.cwiseAbs() * (0.5 * local.extents());
    return {centre - half, centre + half};
}

Aabb shapeLocalBounds(const Shape& shape) {
    switch (shape.type) {
        case ShapeType::None:
            return {};
        case ShapeType::Sphere:
            return centredBox(Vec3::Constant(std::abs(shape.radius)));
        case ShapeType::Box:
            return centredBox(0.5 * shape.size.cwiseAbs());
        case ShapeType::Capsule: {
            const double r = std::abs(shape.radius);
            return centredBox(Vec3(r, r + 0.5 * std::abs(shape.length), r));
        }
        case ShapeType::Cylinder: {
            const double r = std::abs(shape.radius);
            return centredBox(Vec3(r, 0.5 * std::abs(shape.length), r));
        }
        case ShapeType::Plane:
            return infiniteBox();
        case ShapeType::Mesh:
            if (shape.localBounds.isEmpty() && shape.mesh) {
                // Builders fill localBounds; a mesh made by hand still gets its true box.
                Aabb bounds;
                for (const Vec3& v : shape.mesh->vertices)
                    bounds.grow(v);
                return bounds;
            }
            return shape.localBounds;
        case ShapeType::Heightfield:
        case ShapeType::Spline:
            return shape.localBounds;
    }
    return {};
}

Aabb shapeBounds(const Shape& shape, const Vec3& position, const Quat& orientation) {
    switch (shape.type) {
        case ShapeType::None:
            return {};
        case ShapeType::Plane:
            return infiniteBox();
        case ShapeType::Sphere: {
            // Rotation does not matter: skip the matrix.
            const Vec3 r = Vec3::Constant(std::abs(shape.radius));
            return {position - r, position + r};
        }
        case ShapeType::Capsule: {
            // The segment's box grown by the radius: tighter than turning the local box.
            const Vec3 tip = (0.5 * std::abs(shape.length)) * (orientation * Vec3::UnitY());
            const Vec3 half = tip.cwiseAbs() + Vec3::Constant(std::abs(shape.radius));
            return {position - half, position + half};
        }
        case ShapeType::Cylinder: {
            // Along world axis i the axis u reaches ±(length/2)|u_i| and each rim circle
            // ±radius·√(1 − u_i²): tighter than the turned local box for a tilted coin.
            const Vec3 axis = orientation * Vec3::UnitY();
            const Vec3 rim = (Vec3::Ones() - axis.cwiseProduct(axis)).cwiseMax(0.0).cwiseSqrt();
            const Vec3 half =
                (0.5 * std::abs(shape.length)) * axis.cwiseAbs() + std::abs(shape.radius) * rim;
            return {position - half, position + half};
        }
        default:
            return transformedBounds(shapeLocalBounds(shape), position,
                                     orientation.toRotationMatrix());
    }
}

double shapeReach(const Shape& shape) {
    switch (shape.type) {
        case ShapeType::None:
            return 0.0;
        case ShapeType::Plane:
            return std::numeric_limits<double>::infinity();
        case ShapeType::Sphere:
            return std::abs(shape.radius);
        case ShapeType::Capsule:
            return 0.5 * std::abs(shape.length) + std::abs(shape.radius);
        case ShapeType::Cylinder:  // a rim point: the farthest from the centre
            return std::hypot(0.5 * shape.length, shape.radius);
        default: {
            // The farthest corner of the local box bounds every point of the shape.
            const Aabb local = shapeLocalBounds(shape);
            if (local.isEmpty()) return 0.0;
            return local.min.cwiseAbs().cwiseMax(local.max.cwiseAbs()).norm();
        }
    }
}

}  // namespace substep
