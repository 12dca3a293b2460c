#pragma once
// Shared by the soft-body tests: a world with a ground plane, soft-body momenta computed from
// the particles' public state (never from the engine's read-out), and the closed-form static
// deflection of a box lattice standing on the ground.

#include "physics/soft/soft_body.h"
#include "physics/soft/soft_system.h"
#include "physics/world.h"

#include <cmath>

namespace substep::test {

inline constexpr double kG = 10.0;

inline World worldWithGround(int substeps = 20, bool ground = true) {
    World world({.gravity = Vec3(0.0, -kG, 0.0), .substeps = substeps});
    if (ground)
        world.createBody({.shape = planeShape(Vec3::UnitY(), 0.0), .type = BodyType::Static,
                          .staticFriction = 0.8, .dynamicFriction = 0.6});
    return world;
}

/// Σ m v over a soft body's particles.
inline Vec3 softMomentum(const World& world, SoftBodyId id) {
    const SoftSystem& soft = *world.softBodies();
    const auto v = soft.velocities(id);
    const auto m = soft.masses(id);
    Vec3 p = Vec3::Zero();
    for (size_t i = 0; i < v.size(); ++i) p += m[i] * v[i];
    return p;
}

/// Σ m x × v over a soft body's particles, about the origin.
inline Vec3 softAngularMomentum(const World& world, SoftBodyId id) {
    const SoftSystem& soft = *world.softBodies();
    const auto x = soft.positions(id);
    const auto v = soft.velocities(id);
    const auto m = soft.masses(id);
    Vec3 l = Vec3::Zero();
    for (size_t i = 0; i < v.size(); ++i) l += m[i] * x[i].cross(v[i]);
    return l;
}

/// The static shortening of a box lattice of `cells` over `size` standing on the ground under
/// its own weight: each element is a spring of stiffness 1/(4 α_e) between its bottom and top
/// layers (α_e = α ℓ²/V, ℓ² = (a_x² + a_y² + a_z²)/4 for cells a), the layer masses lumped as
/// M_e/2 at the ends and M_e between, so δ = Σ_k 4 α_e g M_e (n − k − ½) = 2 α_e M_e g n² =
/// α ρ g n² (a_x² + a_y² + a_z²) / 2; for cubes, (3/2) α ρ g H² whatever n (docs/SOFT_BODIES.md).
inline double closedFormDeflection(double compliance, double density, const Vec3& size,
                                   const std::array<int, 3>& cells) {
    const Vec3 a(size.x() / cells[0], size.y() / cells[1], size.z() / cells[2]);
    const double n = cells[1];
    return compliance * density * kG * n * n * a.squaredNorm() / 2.0;
}

}  // namespace substep::test
