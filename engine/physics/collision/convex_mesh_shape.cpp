#include "physics/collision/convex_mesh_shape.h"

#include "physics/collision/convex_hull.h"

#include <stdexcept>

namespace substep {

Shape convexMeshShape(std::shared_ptr<const TriangleMesh> mesh) {
    if (!mesh) throw std::invalid_argument("convex mesh: no mesh given");
    auto hull = std::make_shared<ConvexHull>(buildConvexHull(mesh->vertices));
    if (!hull->isSolid()) {
        throw std::invalid_argument(
            "convex mesh: its " + std::to_string(mesh->vertices.size()) +
            " vertices enclose no volume (fewer than 4, or all on one plane or line)");
    }
    Shape shape;
    shape.type = ShapeType::Mesh;
    shape.convex = true;
    shape.localBounds = hull->bounds;
    shape.mesh = std::move(mesh);
    shape.hull = std::move(hull);
    return shape;
}

}  // namespace substep
