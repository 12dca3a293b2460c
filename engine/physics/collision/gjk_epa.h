#pragma once
/// Distance and penetration of two convex cores from their support functions alone.
///
/// GJK (Gilbert, Johnson and Keerthi 1988, in van den Bergen's form) walks simplices of the
/// Minkowski difference A − B towards the origin: the closest point v of A − B to the origin is
/// pA − pB for the closest points of the two cores, and its length their distance. When the
/// simplex encloses the origin the cores overlap, and EPA (the expanding polytope algorithm, van
/// den Bergen 2001) grows a polytope inside A − B from that simplex until its face nearest the
/// origin lies on the boundary: that face's distance is the penetration depth, its normal the
/// axis of least penetration. Both run on fixed arrays (no allocation).

#include "physics/collision/convex_support.h"

namespace substep {

/// The closest (or deepest) pair of the two cores.
struct ConvexDistance {
    Vec3 pointA = Vec3::Zero();  ///< on core A
    Vec3 pointB = Vec3::Zero();  ///< on core B
    /// Unit, from B towards A: the direction A must move to separate (or to separate further).
    Vec3 normal = Vec3::UnitY();
    /// Core distance: > 0 apart (|pA − pB|), < 0 overlapping (minus the penetration depth).
    double separation = 0.0;
    /// True when the cores are certainly farther apart than the cut-off given to the query
    /// (the other fields are then not computed).
    bool beyondCutoff = false;
};

/// The separation of cores A and B with points and normal. Pairs certainly farther apart than
/// `cutoff` return early with beyondCutoff set.
ConvexDistance convexDistance(const ConvexSupport& a, const ConvexSupport& b, double cutoff);

}  // namespace substep
