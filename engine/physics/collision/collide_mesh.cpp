/// Spheres, capsules and boxes against static triangle meshes and heightfields
/// (collide_curved.h). Both sources hand out ContactTriangles near the primitive; the triangle
/// routines (triangle_contact.h) make the points, a ContactBuffer merges the duplicates found
/// from neighbouring triangles and keeps the deepest.

#include "physics/collision/collide_curved.h"
#include "physics/collision/contact_buffer.h"
#include "physics/collision/heightfield.h"
#include "physics/collision/heightfield_sphere.h"
#include "physics/collision/mesh_collider.h"
#include "physics/collision/triangle_contact.h"

namespace substep {

namespace {

/// Two contacts closer than this fraction of the primitive's size are one.
constexpr double kMergeFraction = 0.01;

struct MeshSource {
    const MeshCollider& collider;
    static constexpr bool kSolidBelow = false;
    template <class Visitor>
    void forTrianglesIn(const Aabb& box, Visitor&& visit) const {
        collider.forTrianglesIn(box, [&](int i) { visit(collider.triangle(i)); });
    }
};

struct HeightfieldSource {
    const HeightfieldData& field;
    static constexpr bool kSolidBelow = true;
    template <class Visitor>
    void forTrianglesIn(const Aabb& box, Visitor&& visit) const {
        field.forTrianglesIn(box, visit);
    }
};

template <class Source>
void sphereAgainst(const Source& source, const Shape& a, const Pose& pa, const Pose& pb,
                   double margin, ContactManifold& out) {
    const double r = a.radius;
    const Vec3 c = pb.applyInverse(pa.position);
    ContactBuffer buffer(kMergeFraction * r);
    const Aabb box{c.array() - (r + margin), c.array() + (r + margin)};
    source.forTrianglesIn(box, [&](const ContactTriangle& tri) {
        addSphereTriangleContacts(tri, c, r, margin, Source::kSolidBelow, buffer);
    });
    buffer.emit(pb, out);
}

template <class Source>
void capsuleAgainst(const Source& source, const Shape& a, const Pose& pa, const Pose& pb,
                    double margin, ContactManifold& out) {
    const double r = a.radius;
    const Vec3 halfAxis = 0.5 * a.length * Vec3::UnitY();
    const Vec3 e0 = pb.applyInverse(pa.apply(-halfAxis));
    const Vec3 e1 = pb.applyInverse(pa.apply(halfAxis));
    ContactBuffer buffer(kMergeFraction * r);
    Aabb box;
    box.grow(e0);
    box.grow(e1);
    source.forTrianglesIn(box.inflated(r + margin), [&](const ContactTriangle& tri) {
        addCapsuleTriangleContacts(tri, e0, e1, r, margin, Source::kSolidBelow, buffer);
    });
    buffer.emit(pb, out);
}

template <class Source>
void boxAgainst(const Source& source, const Shape& a, const Pose& pa, const Pose& pb, double margin,
                ContactManifold& out) {
    OrientedBox box;
    box.centre = pb.applyInverse(pa.position);
    box.axes = (pb.rotation.conjugate() * pa.rotation).toRotationMatrix();
    box.half = 0.5 * a.size;
    const Vec3 reach = box.axes.cwiseAbs() * box.half + Vec3::Constant(margin);
    ContactBuffer buffer(kMergeFraction * box.half.minCoeff());
    source.forTrianglesIn({box.centre - reach, box.centre + reach},
                          [&](const ContactTriangle& tri) {
                              addBoxTriangleContacts(tri, box, margin, Source::kSolidBelow, buffer);
                          });
    buffer.emit(pb, out);
}

}  // namespace

void collideSphereMesh(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                       double margin, ContactManifold& out) {
    out.clear();
    if (b.meshCollider) sphereAgainst(MeshSource{*b.meshCollider}, a, pa, pb, margin, out);
}

void collideCapsuleMesh(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                        double margin, ContactManifold& out) {
    out.clear();
    if (b.meshCollider) capsuleAgainst(MeshSource{*b.meshCollider}, a, pa, pb, margin, out);
}

void collideBoxMesh(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, double margin,
                    ContactManifold& out) {
    out.clear();
    if (b.meshCollider) boxAgainst(MeshSource{*b.meshCollider}, a, pa, pb, margin, out);
}

void collideSphereHeightfield(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                              double margin, ContactManifold& out) {
    out.clear();
    // sphereAgainst's points, bit for bit, without a triangle object per cell (heightfield_sphere.h).
    if (b.heightfield) collideSphereHeightfield(HeightfieldGrid(*b.heightfield), pa.position, a.radius, pb, margin, out);
}

void collideCapsuleHeightfield(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                               double margin, ContactManifold& out) {
    out.clear();
    if (b.heightfield) capsuleAgainst(HeightfieldSource{*b.heightfield}, a, pa, pb, margin, out);
}

void collideBoxHeightfield(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                           double margin, ContactManifold& out) {
    out.clear();
    if (b.heightfield) boxAgainst(HeightfieldSource{*b.heightfield}, a, pa, pb, margin, out);
}

}  // namespace substep
