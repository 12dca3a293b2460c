#pragma once
/// The contact patch of a pair with two or more points (contact.h): its pushes, static friction
/// and torsional friction solved as one small system (PatchSystem), in the position solve and
/// in the velocity pass. Internal to the contact solve: solveContactPositions and
/// solveContactVelocities (contact.cpp) dispatch here; one-point pairs stay in contact.cpp.

#include "physics/contact.h"

#include <span>

namespace substep::contact_detail {

/// solveContactPositions for a pair of 2 to kMaxPatchPoints points (`contacts` holds exactly them).
void solvePatchPositions(ContactPair& pair, std::span<Contact> contacts, SolverContext& ctx);

/// solveContactVelocities for a pair of 2 to kMaxPatchPoints points (`contacts` holds exactly them).
void solvePatchVelocities(const ContactPair& pair, std::span<const Contact> contacts, Body& b0, Body& b1,
                          double h, double gravity);

}  // namespace substep::contact_detail
