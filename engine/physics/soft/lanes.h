#pragma once
/// Four doubles operated on together, and the transposes between particles stored as packed
/// Vec3s and x, y, z lanes: the vector kernels of the soft bodies (element_batch.cpp,
/// rigid_mode.cpp) are written with these. GCC vector types, which clang shares: one AVX
/// register, or two SSE2 ones. Shuffles are `__builtin_shufflevector` (0-3 pick the first
/// vector's lanes, 4-7 the second's), which both GCC 12 and clang have. The kernels are compiled
/// for AVX-512VL, AVX2 and the base ISA (`target_clones`), into which these always inline.

#include "physics/math.h"

#include <cstring>

namespace substep::simd {

inline constexpr int kLanes = 4;

/// kLanes doubles.
using Lanes = double __attribute__((vector_size(kLanes * sizeof(double))));

static_assert(sizeof(Vec3) == 3 * sizeof(double), "particles are read as packed doubles");

// Loads and stores through memory (vectors are not passed by value: a different ABI with and
// without AVX).
[[gnu::always_inline]] inline void load(Lanes& v, const double* p) { std::memcpy(&v, p, sizeof v); }
[[gnu::always_inline]] inline void store(double* p, const Lanes& v) { std::memcpy(p, &v, sizeof v); }

/// Σ of the lanes, in a fixed order.
[[gnu::always_inline]] inline double sum(const Lanes& v) { return (v[0] + v[1]) + (v[2] + v[3]); }

/// Four consecutive points' 12 coordinates (x0 y0 z0 x1 | y1 z1 x2 y2 | z2 x3 y3 z3) into x, y
/// and z lanes.
[[gnu::always_inline]] inline void loadPoints(const double* p, Lanes& x, Lanes& y, Lanes& z) {
    Lanes v0, v1, v2;
    load(v0, p), load(v1, p + 4), load(v2, p + 8);
    x = __builtin_shufflevector(__builtin_shufflevector(v0, v1, 0, 3, 6, 0), v2, 0, 1, 2, 5);
    y = __builtin_shufflevector(__builtin_shufflevector(v0, v1, 1, 4, 7, 0), v2, 0, 1, 2, 6);
    z = __builtin_shufflevector(__builtin_shufflevector(v0, v1, 2, 5, 0, 0), v2, 0, 1, 4, 7);
}

/// The inverse of loadPoints.
[[gnu::always_inline]] inline void storePoints(double* p, const Lanes& x, const Lanes& y, const Lanes& z) {
    const Lanes xy01 = __builtin_shufflevector(x, y, 0, 4, 1, 5);  // x0 y0 x1 y1
    const Lanes xy23 = __builtin_shufflevector(x, y, 2, 6, 3, 7);  // x2 y2 x3 y3
    const Lanes yz12 = __builtin_shufflevector(y, z, 1, 5, 2, 6);  // y1 z1 y2 z2
    store(p, __builtin_shufflevector(xy01, z, 0, 1, 4, 2));
    store(p + 4, __builtin_shufflevector(yz12, xy23, 0, 1, 4, 5));
    const Lanes xyz23 = __builtin_shufflevector(xy23, z, 2, 3, 6, 7);  // x3 y3 z2 z3
    store(p + 8, __builtin_shufflevector(xyz23, xyz23, 2, 0, 1, 3));
}

}  // namespace substep::simd
