#pragma once
/// One-point contacts four at a time: the position solve (Eq. 26 to Eq. 28) and the velocity
/// pass (Eq. 29, Eq. 30, Eq. 33, Eq. 34) of up to four one-point pairs that share no moving body,
/// each pair in one lane of four-double vectors. contact.cpp's scheduler gathers such groups from
/// the touching list where Gauss-Seidel's order allows it.
///
/// Why lanes: one point's solve is a chain of rotations, square roots and divisions, each waiting
/// for the one before; four chains in the lanes of the same instructions wait once for all four
/// and take about a third of the instructions (a sphere pile is mostly such points).
///
/// Every lane takes the scalar path's operations (contact.cpp) in the scalar path's order, Eigen's
/// for its vectors and quaternions, and a masked lane keeps its old value rather than adding a
/// zero: each pair comes out with the same bits as solved alone. The rare turns beyond the
/// series of integrateRotation go through it lane by lane. Internal to the contact solve.

#include "physics/contact.h"

#include <cstdint>
#include <span>

namespace substep::contact_detail {

/// Most pairs one call takes.
inline constexpr int kContactLanes = 4;

/// The instruction sets the lanes are compiled for, narrowest first: the base ISA solves the
/// pairs one by one, with the scalar path. Each gives the same bits (no fused multiply-adds);
/// the widest the CPU has is used.
enum class LaneIsa : uint8_t { Base, Avx2, Avx512 };

/// The widest LaneIsa this CPU runs.
LaneIsa widestLaneIsa();

/// Makes the calls below use `isa` (at most the widest) and returns the one used before: for
/// the tests, which compare every one with the scalar path, and the benchmarks. Not thread-safe:
/// call it while no step runs.
LaneIsa useLaneIsa(LaneIsa isa);

/// solveContactPositions (Gauss-Seidel) of `count` one-point pairs, 1 ≤ count ≤ kContactLanes,
/// that share no moving body.
void solveOnePointPositionsInLanes(ContactPair* const* pairs, int count, std::span<Contact> contacts,
                                   SolverContext& ctx);

/// solveContactVelocities of `count` one-point pairs, 1 ≤ count ≤ kContactLanes, that share no
/// moving body and whose point is not in the collision pass (Contact::collisionPass).
void solveOnePointVelocitiesInLanes(const ContactPair* const* pairs, int count, std::span<const Contact> contacts,
                                    Body* bodies, double h, double gravity);

}  // namespace substep::contact_detail
