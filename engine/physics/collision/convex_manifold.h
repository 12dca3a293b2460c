#pragma once
/// The general convex pair: GJK/EPA for the deepest pair and the normal (gjk_epa.h), then a
/// manifold by clipping the two shapes' support features (Jolt's approach): the feature of B
/// along the normal and of A against it (a face, an edge, a point, convex_support.h). A face
/// turned within kReferenceCosine of the normal is the reference; the other feature is clipped
/// against the side planes of its polygon and every clipped point measured along the normal to
/// the reference plane. A cylinder flat on a box or a hull face to face so rest on several
/// points, up to 4 that span the patch best; two near-parallel lines (capsule or cylinder side
/// by side) touch at the ends of their overlap. Where no feature is flat enough, the deepest
/// pair is the one contact.

#include "physics/collision/contact_manifold.h"
#include "physics/collision/convex_support.h"
#include "physics/collision/gjk_epa.h"

namespace substep {

/// A face serves as the reference when its normal lies within this cosine of the contact
/// normal (about 10°): the points clipped against it are then measured along a direction near
/// its own normal.
inline constexpr double kReferenceCosine = 0.985;
/// Two edges are side by side when the sine between them is below this.
inline constexpr double kParallelEdgeSine = 0.02;
/// The general pair keeps at most this many points (those spanning the largest area).
inline constexpr int kGeneralContactPoints = 4;

/// Appends to `out` the contacts of convex A against convex B around their deepest pair
/// `deepest` (from convexDistance or any pair with a normal from B towards A): normal from B
/// towards A, depth = (point1 − point0)·normal with the radii included, points with depth of at
/// least −margin. `featureBase` is added to every point's feature id.
void buildConvexManifold(const ConvexSupport& a, const ConvexSupport& b,
                         const ConvexDistance& deepest, double margin, uint32_t featureBase,
                         ContactManifold& out);

/// Appends `count` candidate points to `out`, reduced to the kGeneralContactPoints spanning the
/// largest area (the deepest, the farthest from it, the largest triangle, the most added).
void appendSpanningPoints(const ContactPoint* candidates, int count, ContactManifold& out);

/// Distance and manifold in one call; nothing when the shapes are more than `margin` apart.
void collideConvexSupports(const ConvexSupport& a, const ConvexSupport& b, double margin,
                           ContactManifold& out);

/// The narrowphase pair function for any two convex shapes (sphere, capsule, box, cylinder,
/// convex mesh) at their poses: shape a is shape 0, the normal from b towards a.
void collideGeneralConvex(const Shape& a, const Pose& pa, const Shape& b, const Pose& pb,
                          double margin, ContactManifold& out);

}  // namespace substep
