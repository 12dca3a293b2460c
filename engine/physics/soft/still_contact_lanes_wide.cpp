// Groups of still contacts in the eight lanes of an AVX-512 register
// (still_contact_lanes_kernel.h).
#include "physics/soft/still_contacts.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

#if !defined(__clang__)
#pragma GCC push_options
#pragma GCC target("arch=x86-64-v4")
#endif
#include "physics/soft/still_contact_lanes_kernel.h"
#if !defined(__clang__)
#pragma GCC pop_options
#endif

namespace substep {

[[gnu::target("arch=x86-64-v4")]] void solveStillPositionsInWideLanes(
    ParticleContact* contacts, size_t count, const ContactParticles& particles,
    const ContactStep& step) {
    for (size_t first = 0; first < count; first += 8)
        stillPositionsInLanes<8>(contacts + first,
                                 static_cast<int>(std::min<size_t>(8, count - first)), particles,
                                 step);
}

[[gnu::target("arch=x86-64-v4")]] void solveStillVelocitiesInWideLanes(
    const ParticleContact* contacts, size_t count, const ContactParticles& particles,
    const ContactStep& step) {
    for (size_t first = 0; first < count; first += 8)
        stillVelocitiesInLanes<8>(contacts + first,
                                  static_cast<int>(std::min<size_t>(8, count - first)), particles,
                                  step);
}

}  // namespace substep
