#pragma once
/// Graph colouring of constraints for the parallel solve (WorldSettings::threads).
///
/// Gauss-Seidel solves one constraint after another, each on the bodies as the ones before left
/// them. Two constraints that share no moving body commute exactly: neither reads what the other
/// writes. So the constraints are split into colours in which no two share a dynamic body, and a
/// colour's constraints can be solved in any order, on any threads, with the same bytes. Static
/// bodies (inverse mass 0) are read and never written, so they do not count: every sphere of a
/// pile may touch the floor in the same colour. Colours are solved one after another.
///
/// As in Box2D v3's constraint graph (learned from, not copied): each body keeps a bit per
/// colour it already appears in, and a constraint takes the first colour in which neither of its
/// dynamic bodies appears. A constraint that fits none goes to the overflow, solved serially
/// after the colours. The colouring follows the constraints' order, so it is deterministic.

#include "physics/contact_schedule.h"

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace substep {

/// Assigns colours to constraints between pairs of bodies, one constraint after another.
class ConstraintColouring {
public:
    /// Colours available; one more index, kOverflow, holds what fits none.
    static constexpr int kColours = 32;
    static constexpr uint8_t kOverflow = kColours;

    /// Starts a colouring over bodies [0, bodyCount), none in any colour yet. Keeps its storage
    /// from one colouring to the next.
    void begin(size_t bodyCount);
    /// The colour of the next constraint, joining body0 and body1; a body that does not move
    /// (dynamic false) does not count. A constraint with no dynamic body takes colour 0.
    uint8_t assign(uint32_t body0, bool dynamic0, uint32_t body1, bool dynamic1) {
        const uint32_t used = (dynamic0 ? colours_[body0] : 0u) | (dynamic1 ? colours_[body1] : 0u);
        if (used == ~0u) return kOverflow;
        const auto colour = static_cast<uint8_t>(std::countr_one(used));
        if (dynamic0) colours_[body0] |= 1u << colour;
        if (dynamic1) colours_[body1] |= 1u << colour;
        return colour;
    }

private:
    static_assert(kColours == 32, "one 32-bit mask per body");
    std::vector<uint32_t> colours_;  ///< per body: the colours it appears in, a bit each
};

/// Items (constraint indices) grouped by colour, each group in the items' given order, the
/// overflow last: the solve order of the coloured step.
class ColourGroups {
public:
    static constexpr int kGroups = ConstraintColouring::kColours + 1;  ///< the overflow is the last
    static constexpr int kOverflowGroup = ConstraintColouring::kOverflow;

    /// Groups `items` by colourOf[item]. Allocates only when more items come than ever before.
    void group(std::span<const uint32_t> items, const uint8_t* colourOf);
    /// Groups the items [0, count) by colourOf[item], leaving out those whose colour is kSkip.
    void groupAll(size_t count, const uint8_t* colourOf);
    /// A colour that groupAll leaves out (a dead joint).
    static constexpr uint8_t kSkip = 0xff;

    /// Group g's items (g < kGroups; kGroups − 1 is the overflow).
    std::span<const uint32_t> operator[](int g) const {
        return std::span<const uint32_t>(items_).subspan(offsets_[g], offsets_[g + 1] - offsets_[g]);
    }
    /// Every item, colour by colour.
    std::span<const uint32_t> all() const { return std::span<const uint32_t>(items_).first(offsets_[kGroups]); }
    /// Groups holding at least one item (overflow included).
    int usedGroups() const;

    /// Items per colour in one block of items (kSkip not counted).
    using Counts = std::array<uint32_t, kGroups>;
    /// Counts a block's items by colourOf[item] into `counts`.
    static void count(std::span<const uint32_t> items, const uint8_t* colourOf, Counts& counts);
    /// Grouping in parallel, items given as blocks in order: with every block's counts (count())
    /// in `counts`, makes room and turns each block's counts into where its items of each colour
    /// go; then placeBlock(block's items, colourOf, counts[block]) for every block, on any
    /// thread and in any order (each block writes its own slots), groups them exactly as group()
    /// groups the blocks joined in order.
    void beginBlocks(std::span<Counts> counts);
    void placeBlock(std::span<const uint32_t> items, const uint8_t* colourOf, Counts& starts);

private:
    void place(size_t count, const uint32_t* items, const uint8_t* colourOf);
    std::vector<uint32_t> items_;
    std::array<uint32_t, kGroups + 1> offsets_{};
};

}  // namespace substep

namespace substep {

/// The coloured step's state (world_parallel.cpp): colours of the frame's contact pairs and
/// joints, and this substep's touching pairs and the frame's joints grouped by colour.
struct ColouredSolve {
    ConstraintColouring colouring;
    std::vector<uint8_t> pairColours;   ///< per contact pair of the frame
    std::vector<uint8_t> jointColours;  ///< per joint slot (ColourGroups::kSkip: dead)
    ColourGroups touching;              ///< this substep's touching pairs
    ContactSchedule overflow;           ///< the overflow's touching pairs, which may share bodies
    /// The parallel narrowphase grouped this substep's touching pairs already (per block of
    /// pairs: its touching pairs' counts by colour, then where they go).
    bool touchingGrouped = false;
    std::vector<ColourGroups::Counts> blockCounts;
    ColourGroups joints;                ///< the frame's live joints
    /// Where thread t's share of every colour of touching pairs begins: at pair index
    /// threadFirstPair[t] (one more entry, ~0, ends the last share).
    std::vector<uint32_t> threadFirstPair;
};

}  // namespace substep
