#pragma once
/// The substeps' first test of a soft body's contact candidates (SoftSystem::findContacts): a
/// particle's distance to a static shape changes by at most its own displacement, so a pair whose
/// gap when the frame began, less how far the particle has moved since, still exceeds the contact
/// margin cannot touch in this substep. A rolling tyre skips about four of its five candidates
/// here, at random, every substep.
///
/// The candidates' skip data is kept apart from the rest of their records, one array per field,
/// so that the test reads 36 bytes of each and runs eight candidates at a time in AVX-512 lanes
/// (their particles' positions gathered, the kept ones' indices compressed into the list).

#include "physics/math.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace substep {

/// Each candidate's particle sphere's gap to a static body's shape when the frame began (m; −∞
/// for a moving body, never skipped), where the particle was then, and the particle.
struct CandidateSkips {
    std::vector<double> originX, originY, originZ, gap;
    std::vector<uint32_t> particle;

    size_t size() const { return particle.size(); }
    void clear();
    void add(const Vec3& origin, double gapAtStart, uint32_t particleIndex);
    /// Moves entry `from` to `to` (to ≤ from) and keeps the first `count`: a filter in place.
    void move(size_t from, size_t to);
    void resize(size_t count);
};

/// How the test runs: eight candidates at a time where the CPU has x86-64-v4 (AVX-512), one at a
/// time otherwise; or one at a time whatever the CPU. Both keep the same candidates.
enum class SkipLanes { Widest, One };

/// Writes to `kept` (room for skips.size()), in order, the index of every candidate that is not
/// skipped: not (gap − margin > 0 and |x[particle] − origin|² < (gap − margin)²), the squared
/// norm summed as Eigen's (x² + y²) + z². Returns how many.
size_t keepUnskipped(const CandidateSkips& skips, const Vec3* x, double margin, uint32_t* kept,
                     SkipLanes lanes = SkipLanes::Widest);

}  // namespace substep
