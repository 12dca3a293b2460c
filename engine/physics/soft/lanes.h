#pragma once
/// Four doubles operated on together, and the transposes between particles stored as packed
/// Vec3s and x, y, z lanes: the vector kernels of the soft bodies (element_batch.cpp,
/// rigid_mode.cpp) are written with these. GCC vector types: one AVX register, or two SSE2
/// ones; the kernels are compiled for AVX-512VL, AVX2 and the base ISA (`target_clones`),
/// into which these always inline.

#include "physics/math.h"

#include <cstring>

namespace substep::simd {

inline constexpr int kLanes = 4;

/// kLanes doubles.
using Lanes = double __attribute__((vector_size(kLanes * sizeof(double))));
/// The lane indices of a shuffle (__builtin_shuffle: 0-3 the first vector's, 4-7 the second's).
using LaneIndex = long long __attribute__((vector_size(kLanes * sizeof(long long))));

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
    x = __builtin_shuffle(__builtin_shuffle(v0, v1, LaneIndex{0, 3, 6, 0}), v2, LaneIndex{0, 1, 2, 5});
    y = __builtin_shuffle(__builtin_shuffle(v0, v1, LaneIndex{1, 4, 7, 0}), v2, LaneIndex{0, 1, 2, 6});
    z = __builtin_shuffle(__builtin_shuffle(v0, v1, LaneIndex{2, 5, 0, 0}), v2, LaneIndex{0, 1, 4, 7});
}

/// The inverse of loadPoints.
[[gnu::always_inline]] inline void storePoints(double* p, const Lanes& x, const Lanes& y, const Lanes& z) {
    const Lanes xy01 = __builtin_shuffle(x, y, LaneIndex{0, 4, 1, 5});  // x0 y0 x1 y1
    const Lanes xy23 = __builtin_shuffle(x, y, LaneIndex{2, 6, 3, 7});  // x2 y2 x3 y3
    const Lanes yz12 = __builtin_shuffle(y, z, LaneIndex{1, 5, 2, 6});  // y1 z1 y2 z2
    store(p, __builtin_shuffle(xy01, z, LaneIndex{0, 1, 4, 2}));
    store(p + 4, __builtin_shuffle(yz12, xy23, LaneIndex{0, 1, 4, 5}));
    store(p + 8, __builtin_shuffle(__builtin_shuffle(xy23, z, LaneIndex{2, 3, 6, 7}), LaneIndex{2, 0, 1, 3}));
}

}  // namespace substep::simd
