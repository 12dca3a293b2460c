// The narrowphase dispatch table: one slot per ordered pair of shape types, built at compile
// time from the list of implemented pairs below. A pair listed as (A, B) fills slot [A][B]
// directly and slot [B][A] as "swapped": collide() then calls the function with the shapes
// exchanged and flips the normals and the two points of each contact.

#include "physics/collision/narrowphase.h"

#include "physics/collision/collide_convex.h"
#include "physics/collision/collide_cylinder.h"
#include "physics/collision/collide_curved.h"
#include "physics/collision/collide_general.h"
#include "physics/collision/convex_hull.h"
#include "physics/collision/convex_manifold.h"
#include "physics/collision/collide_primitives.h"

#include <array>
#include <utility>

namespace substep {

namespace {

// A Mesh shape is either a dynamic convex hull (convex = true) or a static triangle mesh with a
// BVH; these pick the pair function by the mesh's kind.
void collideSphereAnyMesh(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                          double margin, ContactManifold& out) {
    if (b.convex) collideSphereConvex(a, pa, b, pb, margin, out);
    else collideSphereMesh(a, pa, b, pb, margin, out);
}

/// A capsule against a hull takes the general pair: a quarter of the time of the special
/// routine's searches along the segment (docs/PERFORMANCE_LOG.md, "General convex pair").
void collideCapsuleAnyMesh(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                           double margin, ContactManifold& out) {
    if (b.convex) collideGeneralConvex(a, pa, b, pb, margin, out);
    else collideCapsuleMesh(a, pa, b, pb, margin, out);
}

/// Hulls with more faces than this meet other hulls through the general pair: the separating
/// axes grow with faces × faces and edges × edges, GJK/EPA with the support climbs (a rounded
/// 200-vertex hull pair: 59 µs against 5.9 µs).
constexpr std::size_t kGeneralHullFaces = 32;

bool isLargeHull(const Shape& shape) {
    return shape.hull && shape.hull->faces.size() > kGeneralHullFaces;
}

void collideBoxAnyMesh(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                       double margin, ContactManifold& out) {
    if (b.convex) collideBoxConvex(a, pa, b, pb, margin, out);
    else collideBoxMesh(a, pa, b, pb, margin, out);
}

/// Swaps the roles of the two shapes in `out` (the table's reversed slot, by hand).
void flipContacts(ContactManifold& out) {
    for (int k = 0; k < out.count; ++k) {
        ContactPoint& p = out.points[k];
        std::swap(p.point0, p.point1);
        p.normal = -p.normal;
    }
}

/// Hull against hull (separating axes), a hull against a triangle mesh (the general pair per
/// triangle) in either order; two triangle meshes are static and never meet.
void collideMeshMesh(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                     double margin, ContactManifold& out) {
    if (a.convex && b.convex) {
        if (isLargeHull(a) || isLargeHull(b)) collideGeneralConvex(a, pa, b, pb, margin, out);
        else collideConvexConvex(a, pa, b, pb, margin, out);
    } else if (a.convex) {
        collideConvexTriangleMesh(a, pa, b, pb, margin, out);
    } else if (b.convex) {
        collideConvexTriangleMesh(b, pb, a, pa, margin, out);
        flipContacts(out);
    }
}

/// A cylinder against a hull or a triangle mesh: the general pair, whole or per triangle.
void collideCylinderAnyMesh(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                            double margin, ContactManifold& out) {
    if (b.convex) collideGeneralConvex(a, pa, b, pb, margin, out);
    else collideConvexTriangleMesh(a, pa, b, pb, margin, out);
}

/// Only a hull (dynamic) meets a heightfield or a spline; a triangle mesh is static like them.
void collideMeshHeightfield(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                            double margin, ContactManifold& out) {
    if (a.convex) collideConvexHeightfield(a, pa, b, pb, margin, out);
}

void collideMeshSpline(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                       double margin, ContactManifold& out) {
    if (a.convex) collideConvexSpline(a, pa, b, pb, margin, out);
}

/// A triangle mesh is static, like the plane, so only a hull meets a plane.
void collideMeshPlane(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                      double margin, ContactManifold& out) {
    if (a.convex) collideConvexPlane(a, pa, b, pb, margin, out);
}

struct PairEntry {
    ShapeType a;
    ShapeType b;
    CollideFunction function;  ///< shape of type a first
};

// Every pair the narrowphase handles, once each, shape a's type first. To add a pair, add one
// line here with its function; the reversed order follows. Every shape a dynamic body can have
// (sphere, box, capsule, cylinder, convex mesh) meets every shape; the pairs of two static-only
// shapes (plane, heightfield, spline, triangle mesh) and anything with None are deliberately
// absent: they never collide (narrowphase_test walks the table).
constexpr PairEntry kPairs[] = {
    {ShapeType::Sphere, ShapeType::Sphere, collideSphereSphere},
    {ShapeType::Sphere, ShapeType::Plane, collideSpherePlane},
    {ShapeType::Sphere, ShapeType::Box, collideSphereBox},
    {ShapeType::Sphere, ShapeType::Capsule, collideSphereCapsule},
    {ShapeType::Capsule, ShapeType::Capsule, collideCapsuleCapsule},
    {ShapeType::Capsule, ShapeType::Plane, collideCapsulePlane},
    {ShapeType::Capsule, ShapeType::Box, collideCapsuleBox},
    {ShapeType::Box, ShapeType::Plane, collideBoxPlane},
    {ShapeType::Box, ShapeType::Box, collideBoxBox},
    {ShapeType::Sphere, ShapeType::Mesh, collideSphereAnyMesh},
    {ShapeType::Capsule, ShapeType::Mesh, collideCapsuleAnyMesh},
    {ShapeType::Box, ShapeType::Mesh, collideBoxAnyMesh},
    {ShapeType::Mesh, ShapeType::Mesh, collideMeshMesh},
    {ShapeType::Mesh, ShapeType::Plane, collideMeshPlane},
    {ShapeType::Sphere, ShapeType::Heightfield, collideSphereHeightfield},
    {ShapeType::Capsule, ShapeType::Heightfield, collideCapsuleHeightfield},
    {ShapeType::Box, ShapeType::Heightfield, collideBoxHeightfield},
    {ShapeType::Sphere, ShapeType::Spline, collideSphereSpline},
    {ShapeType::Capsule, ShapeType::Spline, collideCapsuleSpline},
    {ShapeType::Cylinder, ShapeType::Plane, collideCylinderPlane},
    {ShapeType::Cylinder, ShapeType::Box, collideCylinderBox},
    {ShapeType::Cylinder, ShapeType::Sphere, collideCylinderSphere},
    // The general convex pair (GJK/EPA and clipping) where no special routine exists.
    {ShapeType::Cylinder, ShapeType::Capsule, collideGeneralConvex},
    {ShapeType::Cylinder, ShapeType::Cylinder, collideGeneralConvex},
    {ShapeType::Cylinder, ShapeType::Mesh, collideCylinderAnyMesh},
    {ShapeType::Cylinder, ShapeType::Heightfield, collideConvexHeightfield},
    {ShapeType::Cylinder, ShapeType::Spline, collideConvexSpline},
    {ShapeType::Box, ShapeType::Spline, collideConvexSpline},
    {ShapeType::Mesh, ShapeType::Heightfield, collideMeshHeightfield},
    {ShapeType::Mesh, ShapeType::Spline, collideMeshSpline},
};

constexpr int kShapeTypeCount = static_cast<int>(ShapeType::Cylinder) + 1;

struct Slot {
    CollideFunction function = nullptr;
    bool swapped = false;  ///< call with (b, a) and flip the result
};

using Table = std::array<std::array<Slot, kShapeTypeCount>, kShapeTypeCount>;

constexpr Table buildTable() {
    Table table{};
    for (const PairEntry& entry : kPairs) {
        const int a = static_cast<int>(entry.a);
        const int b = static_cast<int>(entry.b);
        table[a][b] = {entry.function, false};
        if (a != b) table[b][a] = {entry.function, true};
    }
    return table;
}

constexpr bool listsEachPairOnce() {
    for (std::size_t i = 0; i < std::size(kPairs); ++i) {
        for (std::size_t k = i + 1; k < std::size(kPairs); ++k) {
            const bool same = kPairs[i].a == kPairs[k].a && kPairs[i].b == kPairs[k].b;
            const bool reversed = kPairs[i].a == kPairs[k].b && kPairs[i].b == kPairs[k].a;
            if (same || reversed) return false;
        }
    }
    return true;
}
static_assert(listsEachPairOnce(), "kPairs lists a pair twice (possibly in reversed order)");

constexpr Table kTable = buildTable();

}  // namespace

void collide(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb, double margin,
             ContactManifold& out) {
    out.clear();
    const Slot& slot = kTable[static_cast<int>(a.type)][static_cast<int>(b.type)];
    if (slot.function == nullptr) return;
    if (!slot.swapped) {
        slot.function(a, pa, b, pb, margin, out);
        return;
    }
    slot.function(b, pb, a, pa, margin, out);
    // The function saw b as shape 0: swap the roles; the depth is unchanged.
    flipContacts(out);
}

bool canCollide(ShapeType a, ShapeType b) {
    return kTable[static_cast<int>(a)][static_cast<int>(b)].function != nullptr;
}

}  // namespace substep
