#include "physics/constraint_colouring.h"

#include <algorithm>

namespace substep {

void ConstraintColouring::begin(size_t bodyCount) { colours_.assign(bodyCount, 0u); }

void ColourGroups::group(std::span<const uint32_t> items, const uint8_t* colourOf) {
    place(items.size(), items.data(), colourOf);
}

void ColourGroups::groupAll(size_t count, const uint8_t* colourOf) { place(count, nullptr, colourOf); }

void ColourGroups::place(size_t count, const uint32_t* items, const uint8_t* colourOf) {
    // A counting sort: stable, so each colour keeps the items' order.
    std::array<uint32_t, kGroups + 1> counts{};
    for (size_t k = 0; k < count; ++k) {
        const uint8_t colour = colourOf[items ? items[k] : k];
        if (colour != kSkip) ++counts[colour + 1];
    }
    for (int g = 0; g < kGroups; ++g) counts[g + 1] += counts[g];
    offsets_ = counts;
    if (items_.size() < counts[kGroups]) items_.resize(counts[kGroups]);
    for (size_t k = 0; k < count; ++k) {
        const auto item = static_cast<uint32_t>(items ? items[k] : k);
        const uint8_t colour = colourOf[item];
        if (colour != kSkip) items_[counts[colour]++] = item;
    }
}

void ColourGroups::count(std::span<const uint32_t> items, const uint8_t* colourOf, Counts& counts) {
    counts.fill(0);
    for (const uint32_t item : items)
        if (colourOf[item] != kSkip) ++counts[colourOf[item]];
}

void ColourGroups::beginBlocks(std::span<Counts> counts) {
    // The counting sort's offsets over all blocks, then each block's start within each colour:
    // the blocks before it in the colour come first, as in the joined order.
    std::array<uint32_t, kGroups + 1> offsets{};
    for (const Counts& block : counts)
        for (int g = 0; g < kGroups; ++g) offsets[g + 1] += block[g];
    for (int g = 0; g < kGroups; ++g) offsets[g + 1] += offsets[g];
    offsets_ = offsets;
    if (items_.size() < offsets[kGroups]) items_.resize(offsets[kGroups]);
    for (Counts& block : counts)
        for (int g = 0; g < kGroups; ++g) {
            const uint32_t items = block[g];
            block[g] = offsets[g];
            offsets[g] += items;
        }
}

void ColourGroups::placeBlock(std::span<const uint32_t> items, const uint8_t* colourOf, Counts& starts) {
    for (const uint32_t item : items) {
        const uint8_t colour = colourOf[item];
        if (colour != kSkip) items_[starts[colour]++] = item;
    }
}

int ColourGroups::usedGroups() const {
    int used = 0;
    for (int g = 0; g < kGroups; ++g) used += offsets_[g + 1] > offsets_[g] ? 1 : 0;
    return used;
}

}  // namespace substep
