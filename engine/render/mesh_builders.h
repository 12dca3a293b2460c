#pragma once
/// Meshes for every shape the physics knows: the primitives at unit size (instances scale them),
/// capsules per radius and length (a capsule does not scale), and meshes built from data:
/// triangle meshes, heightfields and tubes around a curve. The builders take plain arrays, not the
/// physics' collision structs, so the renderer stays independent of the physics.

#include "render/mesh_data.h"

#include <span>

namespace substep::render {

/// Sphere of radius 1 (UV sphere; `rings` latitude bands, `segments` longitude slices).
MeshData unitSphereMesh(int rings = 24, int segments = 48);
/// Cube with edges of length 1 centred on the origin, flat-shaded faces.
MeshData unitBoxMesh();
/// Capsule along y: a cylinder of `length` between two hemispheres of `radius`.
MeshData capsuleMesh(float radius, float length, int rings = 12, int segments = 48);
/// Cylinder of radius 1 along y from y = −0.5 to 0.5, smooth side and flat faces; instances
/// scale it by (radius, length, radius), so one mesh serves every cylinder.
MeshData unitCylinderMesh(int segments = 64);
/// A triangle mesh with flat normals (each triangle gets its own three vertices, so edges of a
/// faceted hull stay crisp). `triangles` holds three indices into `points` per triangle.
MeshData flatShadedMesh(std::span<const Vec3f> points, std::span<const uint32_t> triangles);
/// A heightfield: `columns` x `rows` samples spaced `spacing` apart in x and z, sample (0, 0) at
/// x, z = `corner`; heights[row * columns + column]. Smooth normals; each cell is split along its
/// diagonal from sample (i, j) to (i + 1, j + 1), as the physics splits it.
MeshData heightfieldMesh(int columns, int rows, Vec2f corner, Vec2f spacing, std::span<const float> heights);
/// A tube of `radius` around the polyline `centres` (already sampled from the spline), open ends
/// capped unless `closed` joins the last point to the first. Frames are carried along the curve
/// (parallel transport), so the tube does not twist.
MeshData tubeMesh(std::span<const Vec3f> centres, float radius, bool closed, int segments = 16);

}  // namespace substep::render
