#pragma once
/// Scene files, the shape reader of the loader: a body's `shape` object (sphere, box, capsule,
/// cylinder, plane, mesh, spline, heightfield) into a Shape, and the volume that a density
/// turns into a mass. Internal to the scene library (public entry points: scene_loader.h).

#include "physics/collision/shape.h"
#include "scene/scene_loader_validator.h"

namespace substep::scene_loader {

/// The shape at `node`. Planes, splines, heightfields and non-convex meshes are only allowed
/// when `isStatic`; mesh files are found relative to the folder of `v.file()`.
Shape readShape(const Validator& v, const Node& node, bool isStatic);

/// Volume in m³ (a mesh's that of its closed surface or hull; 0 for shapes without one), to
/// check that density x volume stays within the mass bound.
double shapeVolume(const Shape& shape);

}  // namespace substep::scene_loader
