#pragma once
// The sphere–heightfield narrowphase by brute force, as collide_mesh.cpp computed it before
// heightfield_sphere.cpp: a ContactTriangle for both triangles of every cell
// HeightfieldData::forTrianglesIn visits, each through addSphereTriangleContacts. The reference
// of heightfield_sphere_test.cpp and of BM_ParticleHeightfield.

#include "physics/collision/contact_buffer.h"
#include "physics/collision/heightfield.h"
#include "physics/collision/triangle_contact.h"

namespace substep::reference {

/// A sphere of radius r centred at `centre` (world) on the field at `pose`.
inline void collideSphereHeightfield(const HeightfieldData& field, const Vec3& centre, double r, const Pose& pose,
                                     double margin, ContactManifold& out) {
    out.clear();
    const Vec3 c = pose.applyInverse(centre);
    ContactBuffer buffer(0.01 * r);
    const Aabb box{c.array() - (r + margin), c.array() + (r + margin)};
    field.forTrianglesIn(box, [&](const ContactTriangle& tri) {
        addSphereTriangleContacts(tri, c, r, margin, true, buffer);
    });
    buffer.emit(pose, out);
}

}  // namespace substep::reference
