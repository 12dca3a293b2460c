// Narrowphase pair of a box (shape a) against a plane: the corners below the plane plus
// margin, each an exact vertex-face contact.

#include "physics/collision/collide_primitives.h"
#include "physics/collision/primitive_geometry.h"

namespace substep {

using namespace primitive;

void collideBoxPlane(const Shape& a, const Pose& pa, const Shape& b, const Pose& /*pb*/,
                     double margin, ContactManifold& out) {
    const UnitPlane plane = unitPlane(b);
    const Mat3 rotation = pa.rotation.toRotationMatrix();
    const Vec3 half = halfExtents(a);
    // Corner heights above the plane: the centre's plus the corner offset along the normal.
    const Vec3 localNormal = rotation.transpose() * plane.normal;
    const double centreHeight = plane.normal.dot(pa.position) - plane.offset;

    // The corners within margin, kept sorted deepest first (at most 8, insertion sort).
    int order[8];
    double depth[8];
    int count = 0;
    for (int corner = 0; corner < 8; ++corner) {
        const Vec3 local((corner & 1) ? half.x() : -half.x(), (corner & 2) ? half.y() : -half.y(),
                         (corner & 4) ? half.z() : -half.z());
        const double d = -(centreHeight + localNormal.dot(local));
        if (!(d >= -margin)) continue;
        int k = count++;
        while (k > 0 && depth[k - 1] < d) {
            depth[k] = depth[k - 1];
            order[k] = order[k - 1];
            --k;
        }
        depth[k] = d;
        order[k] = corner;
    }
    // Four corners span any face the box can rest on; more add nothing for the solver.
    for (int k = 0; k < std::min(count, 4); ++k) {
        const int corner = order[k];
        const Vec3 local((corner & 1) ? half.x() : -half.x(), (corner & 2) ? half.y() : -half.y(),
                         (corner & 4) ? half.z() : -half.z());
        const Vec3 point0 = pa.position + rotation * local;
        const double height = plane.normal.dot(point0) - plane.offset;
        addContact(out, point0, point0 - height * plane.normal, plane.normal, margin,
                   static_cast<uint32_t>(corner));
    }
}

}  // namespace substep
