// Groups of still contacts in the four lanes of an AVX2 register (still_contact_lanes_kernel.h).
#include "physics/soft/still_contacts.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

#if !defined(__clang__)
#pragma GCC push_options
#pragma GCC target("avx2")
#endif
#include "physics/soft/still_contact_lanes_kernel.h"
#if !defined(__clang__)
#pragma GCC pop_options
#endif

namespace substep {

[[gnu::target("avx2")]] void solveStillPositionsInLanes(ParticleContact* contacts, size_t count,
                                                        const ContactParticles& particles,
                                                        const ContactStep& step) {
    for (size_t first = 0; first < count; first += 4)
        stillPositionsInLanes<4>(contacts + first,
                                 static_cast<int>(std::min<size_t>(4, count - first)), particles,
                                 step);
}

[[gnu::target("avx2")]] void solveStillVelocitiesInLanes(const ParticleContact* contacts,
                                                         size_t count,
                                                         const ContactParticles& particles,
                                                         const ContactStep& step) {
    for (size_t first = 0; first < count; first += 4)
        stillVelocitiesInLanes<4>(contacts + first,
                                  static_cast<int>(std::min<size_t>(4, count - first)), particles,
                                  step);
}

}  // namespace substep
