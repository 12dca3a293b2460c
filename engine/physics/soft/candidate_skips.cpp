// The candidates' skip test (candidate_skips.h), one candidate at a time and eight at a time.
// Built with -ffp-contract=off: both sum |x − origin|² as (x² + y²) + z² without a fused
// multiply-add, so they keep the same candidates.
#include "physics/soft/candidate_skips.h"

#include "physics/soft/element_batch.h"

#include <immintrin.h>

namespace substep {
namespace {

static_assert(sizeof(Vec3) == 3 * sizeof(double), "positions are read as packed (x, y, z)");

/// Whether candidate i is skipped (candidate_skips.h), the particle's position at p.
[[gnu::always_inline]] inline bool skipped(const CandidateSkips& skips, size_t i, const double* p, double margin) {
    const double slack = skips.gap[i] - margin;
    const double dx = p[0] - skips.originX[i], dy = p[1] - skips.originY[i], dz = p[2] - skips.originZ[i];
    return (slack > 0.0) & ((dx * dx + dy * dy) + dz * dz < slack * slack);
}

/// Candidates [first, end) one at a time, without a branch: a rolling tyre's candidates pass
/// and fail at random, and a mispredicted branch costs more than the test.
size_t keepOneAtATime(const CandidateSkips& skips, const double* x, double margin, size_t first, size_t end,
                      uint32_t* kept, size_t count) {
    for (size_t i = first; i < end; ++i) {
        kept[count] = static_cast<uint32_t>(i);
        count += !skipped(skips, i, x + 3 * size_t(skips.particle[i]), margin);
    }
    return count;
}

/// Eight consecutive points' coordinates into x, y and z lanes: three loads and six permutes.
[[gnu::target("arch=x86-64-v4")]] [[gnu::always_inline]] inline void loadEightPoints(const double* p, __m512d& x,
                                                                                     __m512d& y, __m512d& z) {
    // x0 y0 z0 x1 y1 z1 x2 y2 | z2 x3 y3 z3 x4 y4 z4 x5 | y5 z5 x6 y6 z6 x7 y7 z7
    const __m512d a = _mm512_loadu_pd(p), b = _mm512_loadu_pd(p + 8), c = _mm512_loadu_pd(p + 16);
    // Indices 0-7 pick from the first operand, 8-15 from the second.
    const __m512i xab = _mm512_setr_epi64(0, 3, 6, 9, 12, 15, 0, 0), xc = _mm512_setr_epi64(0, 1, 2, 3, 4, 5, 10, 13);
    const __m512i yab = _mm512_setr_epi64(1, 4, 7, 10, 13, 0, 0, 0), yc = _mm512_setr_epi64(0, 1, 2, 3, 4, 8, 11, 14);
    const __m512i zab = _mm512_setr_epi64(2, 5, 8, 11, 14, 0, 0, 0), zc = _mm512_setr_epi64(0, 1, 2, 3, 4, 9, 12, 15);
    x = _mm512_permutex2var_pd(_mm512_permutex2var_pd(a, xab, b), xc, c);
    y = _mm512_permutex2var_pd(_mm512_permutex2var_pd(a, yab, b), yc, c);
    z = _mm512_permutex2var_pd(_mm512_permutex2var_pd(a, zab, b), zc, c);
}

/// The whole blocks of eight candidates: their particles' coordinates gathered (64-bit indices:
/// 3 p of any particle index fits), the test in lanes, and the kept lanes' indices compressed and
/// stored as a whole vector (`kept` has room: at most i of them precede block i). Returns how many
/// it kept; `done`, how many candidates it tested. It returns to the caller rather than calling
/// the one-at-a-time loop for the rest: GCC 12 put no vzeroupper before such a tail call, and the
/// SSE2 narrowphase after it ran at half speed with the vector registers' upper halves dirty.
[[gnu::target("arch=x86-64-v4")]] size_t keepEightAtATime(const CandidateSkips& skips, const double* x,
                                                          double margin, uint32_t* kept, size_t& done) {
    const size_t n = skips.size();
    const __m512d marginLanes = _mm512_set1_pd(margin), zero = _mm512_setzero_pd();
    const __m256i iota = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
    __m256i index = iota;
    const __m256i eight = _mm256_set1_epi32(8);
    size_t count = 0, i = 0;
    for (; i + 8 <= n; i += 8) {
        const __m256i particles = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(skips.particle.data() + i));
        const uint32_t first = skips.particle[i];
        __m512d px, py, pz;
        if (_mm256_cmpeq_epi32_mask(particles, _mm256_add_epi32(_mm256_set1_epi32(static_cast<int>(first)), iota)) ==
            0xff) {
            loadEightPoints(x + 3 * size_t(first), px, py, pz);  // consecutive particles: rows
        } else {
            const __m512i p = _mm512_cvtepu32_epi64(particles);
            const __m512i p3 = _mm512_add_epi64(p, _mm512_add_epi64(p, p));
            px = _mm512_i64gather_pd(p3, x, 8), py = _mm512_i64gather_pd(p3, x + 1, 8);
            pz = _mm512_i64gather_pd(p3, x + 2, 8);
        }
        const __m512d dx = _mm512_sub_pd(px, _mm512_loadu_pd(skips.originX.data() + i));
        const __m512d dy = _mm512_sub_pd(py, _mm512_loadu_pd(skips.originY.data() + i));
        const __m512d dz = _mm512_sub_pd(pz, _mm512_loadu_pd(skips.originZ.data() + i));
        const __m512d moved2 =
            _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(dx, dx), _mm512_mul_pd(dy, dy)), _mm512_mul_pd(dz, dz));
        const __m512d slack = _mm512_sub_pd(_mm512_loadu_pd(skips.gap.data() + i), marginLanes);
        const __mmask8 skip = _mm512_cmp_pd_mask(slack, zero, _CMP_GT_OQ) &
                              _mm512_cmp_pd_mask(moved2, _mm512_mul_pd(slack, slack), _CMP_LT_OQ);
        const __mmask8 keep = static_cast<__mmask8>(~skip);
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(kept + count), _mm256_maskz_compress_epi32(keep, index));
        count += static_cast<size_t>(__builtin_popcount(keep));
        index = _mm256_add_epi32(index, eight);
    }
    done = i;
    return count;
}

}  // namespace

void CandidateSkips::clear() {
    originX.clear(), originY.clear(), originZ.clear(), gap.clear(), particle.clear();
}

void CandidateSkips::add(const Vec3& origin, double gapAtStart, uint32_t particleIndex) {
    originX.push_back(origin.x()), originY.push_back(origin.y()), originZ.push_back(origin.z());
    gap.push_back(gapAtStart);
    particle.push_back(particleIndex);
}

void CandidateSkips::move(size_t from, size_t to) {
    originX[to] = originX[from], originY[to] = originY[from], originZ[to] = originZ[from];
    gap[to] = gap[from];
    particle[to] = particle[from];
}

void CandidateSkips::resize(size_t count) {
    originX.resize(count), originY.resize(count), originZ.resize(count), gap.resize(count), particle.resize(count);
}

size_t keepUnskipped(const CandidateSkips& skips, const Vec3* x, double margin, uint32_t* kept, SkipLanes lanes) {
    if (skips.size() == 0) return 0;
    const double* const positions = x->data();
    size_t done = 0, count = 0;
    if (lanes == SkipLanes::Widest && wideElementLanes()) count = keepEightAtATime(skips, positions, margin, kept, done);
    return keepOneAtATime(skips, positions, margin, done, skips.size(), kept, count);
}

}  // namespace substep
