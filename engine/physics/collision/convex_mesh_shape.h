#pragma once
/// Building a convex-mesh shape: a mesh that collides and weighs as its convex hull.

#include "physics/collision/shape.h"

#include <memory>

namespace substep {

/// A mesh shape with convex = true, its hull built from the mesh's vertices and localBounds
/// set to the hull's bounds. Throws std::invalid_argument when the mesh is null or its vertices
/// span no volume (fewer than 4, coplanar, collinear) or are not finite.
Shape convexMeshShape(std::shared_ptr<const TriangleMesh> mesh);

}  // namespace substep
