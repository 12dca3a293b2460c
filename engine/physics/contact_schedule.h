#pragma once
/// The order in which a substep's touching pairs are solved, and the two passes that follow it.
///
/// Gauss-Seidel's order binds only corrections that share a moving body. So a one-point pair may
/// be solved together with up to kContactLanes − 1 later one-point pairs, in the lanes of the
/// same vector instructions (contact_lanes.h), as long as none of them shares a moving body with
/// another or with a pair it passes that is still to be solved (that pair keeps its place).
/// Every body then sees its corrections in the listed order, and every pass gives the bytes of
/// solving the list one pair at a time. The schedule is planned once per substep, after the
/// narrowphase, for the position solve and the velocity pass alike (its pairs, their bodies and
/// point counts do not change between them).
///
/// A colour of the parallel solve (constraint_colouring.h) shares no moving body at all: its
/// one-point pairs go into lanes as they come (solveIndependentPositions and -Velocities).

#include "physics/contact.h"

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace substep {

class ContactSchedule {
public:
    /// Plans `touching` (indices into `pairs`, in their order) for the pairs' current bodies.
    void plan(std::span<const uint32_t> touching, std::span<const ContactPair> pairs, std::span<const Body> bodies);

    /// The planned pairs in their listed order (Jacobi, whose gathered sums keep that order).
    std::span<const uint32_t> touching() const { return touching_; }

    /// The steps: each the number of pairs it takes together (1 to kContactLanes), then their
    /// indices.
    std::span<const uint32_t> steps() const { return std::span<const uint32_t>(steps_).first(stepsLength_); }

private:
    /// A touching pair as the planning sees it: its moving bodies (~0 for one that does not move).
    struct Candidate {
        uint32_t moving0;
        uint32_t moving1;
        uint32_t onePoint;  ///< 1 for a one-point pair
        bool operator==(const Candidate&) const = default;
    };

    std::vector<uint32_t> touching_;
    std::vector<uint32_t> steps_;  ///< the steps in its first stepsLength_ entries
    size_t stepsLength_ = 0;
    std::vector<Candidate> candidates_;  ///< the planned pairs' candidates
    std::vector<Candidate> next_;        ///< scratch of plan(): this substep's candidates
    /// Per body: the step it was last blocked for (plan()); mark_ is the current step's.
    std::vector<uint32_t> blockedMark_;
    uint32_t mark_ = 0;
};

/// The position solve of the planned pairs: solveContactPositions of each, in the schedule's
/// steps for Gauss-Seidel (one-point pairs together in lanes), in the listed order for Jacobi.
void solveTouchingPositions(const ContactSchedule& schedule, std::span<ContactPair> pairs,
                            std::span<Contact> contacts, SolverContext& ctx);

/// The velocity pass of the planned pairs: solveContactVelocities of each, in the schedule's
/// steps (a point in the collision pass leaves its step's lanes and is solved alone).
void solveTouchingVelocities(const ContactSchedule& schedule, std::span<const ContactPair> pairs,
                             std::span<const Contact> contacts, Body* bodies, double h, double gravity);

/// solveTouchingPositions for pairs that share no moving body with one another (a colour of the
/// parallel solve), in their order: their one-point pairs are taken kContactLanes at a time.
void solveIndependentPositions(std::span<const uint32_t> independent, std::span<ContactPair> pairs,
                               std::span<Contact> contacts, SolverContext& ctx);

/// solveTouchingVelocities for pairs that share no moving body with one another.
void solveIndependentVelocities(std::span<const uint32_t> independent, std::span<const ContactPair> pairs,
                                std::span<const Contact> contacts, Body* bodies, double h, double gravity);

}  // namespace substep
