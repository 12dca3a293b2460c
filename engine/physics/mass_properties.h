#pragma once
/// Mass, centre of mass and inertia of shapes, and the principal frame that makes the inertia
/// diagonal (paper 3.3.2: bodies are simulated in a rest frame where I is a vector).

#include "physics/collision/shape.h"
#include "physics/math.h"

namespace substep {

/// Mass properties in the shape's own frame; `inertia` is taken about the centre of mass.
struct MassProperties {
    double mass = 0.0;
    Vec3 centerOfMass = Vec3::Zero();
    Mat3 inertia = Mat3::Zero();
};

/// The principal frame of an inertia tensor: I = R diag(moments) Rᵀ with R = rotation.
/// `rotation` turns principal-frame vectors into shape-frame vectors and is a proper rotation.
struct PrincipalFrame {
    Vec3 moments = Vec3::Zero();
    Quat rotation = Quat::Identity();
};

MassProperties sphereMassProperties(double radius, double density);
MassProperties boxMassProperties(const Vec3& size, double density);
/// Capsule with its segment along local y: a cylinder of `length` and two hemispherical caps.
MassProperties capsuleMassProperties(double radius, double length, double density);
/// Solid cylinder with its axis along local y: axial m r²/2, transverse m (3r² + l²)/12.
MassProperties cylinderMassProperties(double radius, double length, double density);
/// Closed triangle mesh of uniform density (Blow and Binstock's method: signed tetrahedra
/// against one apex give volume, first and second moments in one pass). A mesh whose triangles
/// wind inside out gives a negative volume: it is flipped, so either winding works. A mesh that
/// encloses no volume (flat, empty) gives mass 0.
MassProperties meshMassProperties(const TriangleMesh& mesh, double density);
/// Mass properties of any shape that can be dynamic; planes and empty shapes give mass 0.
MassProperties shapeMassProperties(const Shape& shape, double density);

/// Scales density so that the mass becomes `mass` (centre of mass unchanged). Massless
/// properties (plane, flat mesh) have no density to scale and are returned unchanged.
MassProperties withMass(const MassProperties& properties, double mass);

/// Diagonalises a symmetric inertia tensor (Eigen's self-adjoint solver); moments sorted
/// ascending, rotation right-handed.
PrincipalFrame principalFrame(const Mat3& inertia);

}  // namespace substep
