// Tests engine/physics/constraint_colouring.cpp: over random graphs of dynamic and static bodies,
// no two constraints of a colour share a dynamic body, every constraint is grouped exactly once
// in its colour, in the given order; static bodies do not count; what fits no colour overflows;
// grouping in blocks (the parallel narrowphase's) gives the same groups as the joined list.

#include "physics/constraint_colouring.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <algorithm>
#include <random>
#include <set>
#include <utility>
#include <vector>

namespace substep {
namespace {

struct Graph {
    std::vector<bool> dynamic;                          ///< per body
    std::vector<std::pair<uint32_t, uint32_t>> edges;  ///< per constraint: its bodies
};

/// `bodies` bodies, a fraction of them static, and `constraints` random pairs (a body with
/// itself included, as a joint to the same body may be).
Graph randomGraph(std::mt19937& random, uint32_t bodies, uint32_t constraints, double staticShare) {
    Graph graph;
    for (uint32_t i = 0; i < bodies; ++i) graph.dynamic.push_back(random() % 1000 >= staticShare * 1000);
    for (uint32_t k = 0; k < constraints; ++k) graph.edges.emplace_back(random() % bodies, random() % bodies);
    return graph;
}

std::vector<uint8_t> colourGraph(ConstraintColouring& colouring, const Graph& graph) {
    colouring.begin(graph.dynamic.size());
    std::vector<uint8_t> colours;
    for (const auto& [a, b] : graph.edges) colours.push_back(colouring.assign(a, graph.dynamic[a], b, graph.dynamic[b]));
    return colours;
}

TEST(ConstraintColouringTest, NoTwoConstraintsOfAColourShareADynamicBody) {
    std::mt19937 random(18);
    ConstraintColouring colouring;  // reused: a colouring must not remember the last one
    int overflowed = 0;
    for (int trial = 0; trial < 200; ++trial) {
        const uint32_t bodies = 2 + random() % 300;
        const uint32_t constraints = random() % 2000;
        const Graph graph = randomGraph(random, bodies, constraints, (trial % 5) * 0.2);
        const std::vector<uint8_t> colours = colourGraph(colouring, graph);
        // Per colour, the dynamic bodies seen so far.
        std::vector<std::set<uint32_t>> seen(ConstraintColouring::kColours);
        for (size_t k = 0; k < graph.edges.size(); ++k) {
            ASSERT_LE(colours[k], ConstraintColouring::kOverflow);
            if (colours[k] == ConstraintColouring::kOverflow) {
                ++overflowed;
                continue;
            }
            const auto [a, b] = graph.edges[k];
            std::set<uint32_t>& mine = seen[colours[k]];
            for (const uint32_t body : {a, b}) {
                if (!graph.dynamic[body]) continue;
                // A constraint of a body with itself is one constraint, not two sharing it.
                if (body == b && a == b) continue;
                ASSERT_TRUE(mine.insert(body).second)
                    << "trial " << trial << ": constraint " << k << " shares body " << body << " in colour "
                    << int(colours[k]);
            }
        }
    }
    EXPECT_GT(overflowed, 0) << "the dense graphs must reach the overflow";
}

TEST(ConstraintColouringTest, FirstFreeColourInOrderAndStaticBodiesDoNotCount) {
    ConstraintColouring colouring;
    colouring.begin(50);
    // 40 bodies on one static body (a floor): all in colour 0.
    for (uint32_t i = 1; i <= 40; ++i) EXPECT_EQ(colouring.assign(0, false, i, true), 0);
    // A chain 1-2-3-4: colours 1, 2, 1 (each body already has colour 0 from the floor).
    EXPECT_EQ(colouring.assign(1, true, 2, true), 1);
    EXPECT_EQ(colouring.assign(2, true, 3, true), 2);
    EXPECT_EQ(colouring.assign(3, true, 4, true), 1);
    // 40 constraints around dynamic body 45: colours 0-31, then the overflow.
    for (uint32_t k = 0; k < 40; ++k)
        EXPECT_EQ(colouring.assign(45, true, 0, false),
                  k < 32 ? static_cast<uint8_t>(k) : ConstraintColouring::kOverflow);
    // Two static bodies: colour 0, taking nothing from anyone.
    EXPECT_EQ(colouring.assign(0, false, 46, false), 0);
    EXPECT_EQ(colouring.assign(46, true, 47, true), 0);
    // begin() forgets everything.
    colouring.begin(50);
    EXPECT_EQ(colouring.assign(45, true, 1, true), 0);
}

TEST(ColourGroupsTest, EveryItemOnceInItsColourInOrder) {
    std::mt19937 random(7);
    ColourGroups groups;  // reused with more, then fewer items
    for (const size_t items : {size_t{1000}, size_t{10}, size_t{0}, size_t{3000}}) {
        std::vector<uint8_t> colourOf(4000);
        for (uint8_t& colour : colourOf) colour = static_cast<uint8_t>(random() % ColourGroups::kGroups);
        std::vector<uint32_t> list;  // ascending, with gaps
        for (uint32_t i = 0; i < colourOf.size() && list.size() < items; ++i)
            if (random() % 4 != 0) list.push_back(i);
        groups.group(list, colourOf.data());
        size_t total = 0;
        for (int g = 0; g < ColourGroups::kGroups; ++g) {
            const std::span<const uint32_t> group = groups[g];
            total += group.size();
            for (size_t k = 0; k < group.size(); ++k) {
                EXPECT_EQ(colourOf[group[k]], g);
                if (k > 0) {
                    EXPECT_LT(group[k - 1], group[k]) << "the items' order within a colour";
                }
            }
        }
        EXPECT_EQ(total, list.size());
        EXPECT_EQ(groups.all().size(), list.size());
        std::vector<uint32_t> sorted(groups.all().begin(), groups.all().end());
        std::sort(sorted.begin(), sorted.end());
        EXPECT_EQ(sorted, list) << "every item exactly once";
    }
}

TEST(ColourGroupsTest, GroupAllLeavesOutSkippedItems) {
    const std::vector<uint8_t> colourOf = {2, ColourGroups::kSkip, 0, 2, ColourGroups::kOverflowGroup, 0};
    ColourGroups groups;
    groups.groupAll(colourOf.size(), colourOf.data());
    EXPECT_EQ(std::vector<uint32_t>(groups[0].begin(), groups[0].end()), (std::vector<uint32_t>{2, 5}));
    EXPECT_EQ(std::vector<uint32_t>(groups[2].begin(), groups[2].end()), (std::vector<uint32_t>{0, 3}));
    EXPECT_EQ(std::vector<uint32_t>(groups[ColourGroups::kOverflowGroup].begin(),
                                    groups[ColourGroups::kOverflowGroup].end()),
              (std::vector<uint32_t>{4}));
    EXPECT_EQ(groups.all().size(), 5u);
    EXPECT_EQ(groups.usedGroups(), 3);
}

TEST(ColourGroupsTest, BlocksPlacedInAnyOrderGroupAsTheJoinedList) {
    // The parallel narrowphase's grouping: blocks of a list counted, then placed in any order,
    // give exactly what group() gives on the list (each colour in the list's order).
    std::mt19937 random(7);
    for (const size_t items : {0u, 1u, 50u, 3000u}) {
        std::vector<uint8_t> colourOf(4000);
        for (uint8_t& colour : colourOf)
            colour = random() % 9 == 0 ? ColourGroups::kOverflowGroup : static_cast<uint8_t>(random() % 12);
        std::vector<uint32_t> list;
        for (uint32_t i = 0; i < colourOf.size() && list.size() < items; ++i)
            if (random() % 4 != 0) list.push_back(i);
        ColourGroups joined;
        joined.group(list, colourOf.data());
        for (const size_t blockCount : {1u, 3u, 16u}) {
            std::vector<std::span<const uint32_t>> blocks;
            for (size_t b = 0; b < blockCount; ++b)
                blocks.push_back(std::span<const uint32_t>(list).subspan(list.size() * b / blockCount,
                                                                          list.size() * (b + 1) / blockCount -
                                                                              list.size() * b / blockCount));
            std::vector<ColourGroups::Counts> counts(blockCount);
            for (size_t b = 0; b < blockCount; ++b) ColourGroups::count(blocks[b], colourOf.data(), counts[b]);
            ColourGroups placed;
            placed.beginBlocks(counts);
            for (size_t b = blockCount; b-- > 0;) placed.placeBlock(blocks[b], colourOf.data(), counts[b]);  // last first
            for (int g = 0; g < ColourGroups::kGroups; ++g)
                ASSERT_EQ(std::vector<uint32_t>(placed[g].begin(), placed[g].end()),
                          std::vector<uint32_t>(joined[g].begin(), joined[g].end()))
                    << items << " items in " << blockCount << " blocks, colour " << g;
            EXPECT_EQ(placed.all().size(), list.size());
        }
    }
}

}  // namespace
}  // namespace substep
