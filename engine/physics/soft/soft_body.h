#pragma once
/// Soft bodies: creation settings and the read-out the sandbox reads (paper 4: the RC car's
/// tyres, "per element shape matching [MHTG05] on the 1100 hexahedral elements").
///
/// A soft body is a lattice of particles and 8-particle hexahedral elements. Each element is
/// held to its rest shape, turned by the rotation of its current shape, by one XPBD constraint
/// (shape_matching.h). Its compliance is a material property in 1/Pa, the inverse of a
/// stiffness modulus k: an element of rest volume V whose corners stray from the goal shape by
/// an RMS distance that is a fraction s of its rest RMS corner distance ℓ stores V s² / (2 α).
/// Under uniaxial compression this makes k = 1/(3 α) the element's Young's modulus (no
/// Poisson effect), and a box column of height H standing on the ground shortens by
/// δ = (3/2) α ρ g H² (docs/SOFT_BODIES.md derives it), for one element or n stacked.

#include "physics/handles.h"
#include "physics/math.h"

#include <array>
#include <cstdint>
#include <vector>

namespace substep {

enum class SoftBodyType : uint8_t {
    Box,   ///< a box lattice: `size`, `cells`
    Tyre,  ///< a ring of rectangular cross-section about local y: radii, width, cells
};

/// Which particles an attachment holds.
enum class SoftAttachmentParticles : uint8_t {
    All,    ///< every particle
    Inner,  ///< a tyre's innermost radial layer (a box has none)
    Below,  ///< the particles inside the body's shape at creation
};

/// Holds particles of a soft body to a rigid body at their creation positions relative to it,
/// through the positional correction of Eqs. 2-9 with the particle standing in for a body
/// (w = 1/m, no rotation).
struct SoftAttachmentDef {
    BodyId body;
    SoftAttachmentParticles particles = SoftAttachmentParticles::All;
    double compliance = 0.0;  ///< m/N per attached particle; 0 is hard
};

struct SoftBodyDef {
    SoftBodyType type = SoftBodyType::Box;
    Vec3 size = Vec3(1.0, 1.0, 1.0);  ///< box: full extents (m)
    double outerRadius = 0.5;         ///< tyre (m)
    double innerRadius = 0.3;         ///< tyre (m)
    double width = 0.2;               ///< tyre: along its local y axis (m)
    /// Box: cells along x, y, z. Tyre: cells around, radial, across.
    std::array<int, 3> cells = {1, 1, 1};
    Vec3 position = Vec3::Zero();     ///< of the lattice's centre
    Quat orientation = Quat::Identity();
    Vec3 velocity = Vec3::Zero();
    Vec3 angularVelocity = Vec3::Zero();  ///< rad/s about `position`
    double density = 1000.0;          ///< kg/m³, lumped to the particles
    double compliance = 0.0;          ///< shape matching, 1/Pa (see above); 0: rigid elements
    /// Keep each element's volume: the constraint det F = 1 on the element's best-fit
    /// deformation gradient F, with this compliance in 1/Pa (0: hard). Off by default.
    bool preserveVolume = false;
    double volumeCompliance = 0.0;
    /// 1/s: each element's deformation rate (its corners' velocities less the element's rigid
    /// motion) decays as exp(−k t); rigid motion and the momenta are kept.
    double damping = 0.0;
    double staticFriction = 0.5;
    double dynamicFriction = 0.3;
    double restitution = 0.0;
    double particleRadius = 0.01;     ///< m: particles collide as spheres of this radius
    bool collide = true;
    /// Collision filter against rigid bodies, as BodyDef's (Box2D's category and mask bits): a
    /// particle meets a rigid body only when each one's group is in the other's mask. The
    /// defaults let it meet every body. (A soft body never meets the bodies it is attached to.)
    uint32_t collisionGroup = 1;
    uint32_t collisionMask = ~0u;
    std::vector<SoftAttachmentDef> attachments;
};

/// What the sandbox reads of a soft body (CSV columns, drawing).
struct SoftBodyReadout {
    Vec3 centreOfMass = Vec3::Zero();
    Vec3 velocity = Vec3::Zero();  ///< mass-weighted mean: momentum / mass
    Vec3 extent = Vec3::Zero();    ///< axis-aligned extent of the particle centres (m)
    double volume = 0.0;           ///< Σ current element volumes (m³)
    double mass = 0.0;
    int particles = 0;
    int elements = 0;
};

/// A soft body's surface for drawing: the particle positions and the boundary faces of its
/// lattice, as quads and as the same quads split into triangles, wound counter-clockwise seen
/// from outside.
struct SoftSurface {
    std::vector<Vec3> positions;
    std::vector<std::array<uint32_t, 4>> quads;
    std::vector<std::array<uint32_t, 3>> triangles;
};

}  // namespace substep
