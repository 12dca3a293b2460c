#include "physics/soft/element_batch.h"

#include "physics/soft/shape_matching.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace substep {
namespace {

constexpr int kLanes = kBatchLanes;

/// kLanes doubles operated on together (a GCC vector type: one AVX register, or two SSE2 ones).
using Lanes = double __attribute__((vector_size(kLanes * sizeof(double))));

// Loads and stores through memory (vectors are not passed by value: a different ABI with and
// without AVX).
[[gnu::always_inline]] inline void load(Lanes& v, const double* p) {
    std::memcpy(&v, p, sizeof v);
}

[[gnu::always_inline]] inline void store(double* p, const Lanes& v) {
    std::memcpy(p, &v, sizeof v);
}

/// A lane's Newton step turned more than this (rad²) or met a matrix that is not positive
/// definite: the lane's rotation is finished by extractRotation (as its second iteration would
/// be: what is left after a step of 1e-3 rad is about its square).
constexpr double kLaneTurn2 = 1e-6;

/// Projects one batch: the lanes' arithmetic is written lane-innermost so that the compiler
/// can run the lanes side by side.
[[gnu::always_inline]] inline void solveBatch(const ElementBatch& batch,
                                              const ElementArrays& arrays, double invH2) {
    const uint32_t first = batch.firstElement;
    const int lanes = static_cast<int>(batch.lanes);
    double x[3][8][kLanes];
    double q[4][kLanes], scale2[kLanes], alphaTilde[kLanes], lambda[kLanes];
    for (int l = 0; l < kLanes; ++l) {
        const uint32_t e = first + static_cast<uint32_t>(l < lanes ? l : 0);
        const HexElement& element = arrays.elements[e];
        for (int j = 0; j < 8; ++j) {
            const Vec3& p = arrays.positions[element[j]];
            x[0][j][l] = p.x(), x[1][j][l] = p.y(), x[2][j][l] = p.z();
        }
        const Quat& rotation = arrays.rotations[e];
        q[0][l] = rotation.w(), q[1][l] = rotation.x(), q[2][l] = rotation.y(),
        q[3][l] = rotation.z();
        scale2[l] = arrays.scale2[e];
        alphaTilde[l] = arrays.compliance[e] * invH2;
        lambda[l] = arrays.lambda[e];
    }

    // A = Σ ⅛ x_j q_jᵀ (Σ q_j = 0 removes the centroid).
    double a[3][3][kLanes] = {};
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
            for (int j = 0; j < 8; ++j)
                for (int l = 0; l < kLanes; ++l)
                    a[r][c][l] += x[r][j][l] * batch.rest[c][j][l];
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
            for (int l = 0; l < kLanes; ++l)
                a[r][c][l] *= 0.125;

    // One Newton step of extractRotation from the warm start, in all lanes at once (GCC vector
    // types: selects instead of branches).
    double rot[3][3][kLanes];
    double dq[4][kLanes];  // the quaternion increment ½ scale (0, ω) q
    bool scalar[kLanes];
    {
        Lanes w, qx, qy, qz, spread;
        load(w, q[0]), load(qx, q[1]), load(qy, q[2]), load(qz, q[3]), load(spread, scale2);
        const Lanes r00 = 1 - 2 * (qy * qy + qz * qz), r01 = 2 * (qx * qy - w * qz),
                    r02 = 2 * (qx * qz + w * qy);
        const Lanes r10 = 2 * (qx * qy + w * qz), r11 = 1 - 2 * (qx * qx + qz * qz),
                    r12 = 2 * (qy * qz - w * qx);
        const Lanes r20 = 2 * (qx * qz - w * qy), r21 = 2 * (qy * qz + w * qx),
                    r22 = 1 - 2 * (qx * qx + qy * qy);
        Lanes am[3][3];
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c)
                load(am[r][c], a[r][c]);
        // B = Rᵀ A.
        const Lanes b00 = r00 * am[0][0] + r10 * am[1][0] + r20 * am[2][0];
        const Lanes b01 = r00 * am[0][1] + r10 * am[1][1] + r20 * am[2][1];
        const Lanes b02 = r00 * am[0][2] + r10 * am[1][2] + r20 * am[2][2];
        const Lanes b10 = r01 * am[0][0] + r11 * am[1][0] + r21 * am[2][0];
        const Lanes b11 = r01 * am[0][1] + r11 * am[1][1] + r21 * am[2][1];
        const Lanes b12 = r01 * am[0][2] + r11 * am[1][2] + r21 * am[2][2];
        const Lanes b20 = r02 * am[0][0] + r12 * am[1][0] + r22 * am[2][0];
        const Lanes b21 = r02 * am[0][1] + r12 * am[1][1] + r22 * am[2][1];
        const Lanes b22 = r02 * am[0][2] + r12 * am[1][2] + r22 * am[2][2];
        const Lanes ux = b21 - b12, uy = b02 - b20, uz = b10 - b01;  // 2u
        const Lanes trace = b00 + b11 + b22;
        const Lanes m00 = trace - b00, m11 = trace - b11, m22 = trace - b22;
        const Lanes m01 = -0.5 * (b01 + b10), m02 = -0.5 * (b02 + b20), m12 = -0.5 * (b12 + b21);
        const Lanes c00 = m11 * m22 - m12 * m12, c01 = m02 * m12 - m01 * m22,
                    c02 = m01 * m12 - m02 * m11;
        const Lanes c11 = m00 * m22 - m02 * m02, c12 = m01 * m02 - m00 * m12,
                    c22 = m00 * m11 - m01 * m01;
        const Lanes det = m00 * c00 + m01 * c01 + m02 * c02;
        const Lanes floor = 1e-6 * (trace < 0 ? -trace : trace) + 1e-9 * spread;
        const auto definite = (m00 > floor) & (c22 > floor * floor) & (det > floor * floor * floor);
        const Lanes zero = {};
        const Lanes inverse = definite ? 1.0 / det : zero;
        const Lanes tx = (c00 * ux + c01 * uy + c02 * uz) * inverse;
        const Lanes ty = (c01 * ux + c11 * uy + c12 * uz) * inverse;
        const Lanes tz = (c02 * ux + c12 * uy + c22 * uz) * inverse;
        const Lanes angle2 = tx * tx + ty * ty + tz * tz;
        // Not definite, a turn over 1e-3 rad or NaN: the lane goes to extractRotation.
        const auto handOver = ~definite | (angle2 > kLaneTurn2) | (angle2 != angle2);
        // integrateRotation's small-angle series (|θ|/2 below 5e-4 here); a converged lane
        // (angle2 ≤ 1e-24) stays put, as in extractRotation.
        const Lanes half2 = 0.25 * angle2;
        const Lanes series = 0.5 * (1.0 + half2 * (1.0 / 3.0 + half2 * (2.0 / 15.0)));
        const Lanes scale = (handOver | (angle2 <= 1e-24)) ? zero : series;
        const Lanes ox = (r00 * tx + r01 * ty + r02 * tz) * scale;  // ½ scale ω, ω = R turn
        const Lanes oy = (r10 * tx + r11 * ty + r12 * tz) * scale;
        const Lanes oz = (r20 * tx + r21 * ty + r22 * tz) * scale;
        store(dq[0], -ox * qx - oy * qy - oz * qz);
        store(dq[1], ox * w + oy * qz - oz * qy);
        store(dq[2], -ox * qz + oy * w + oz * qx);
        store(dq[3], ox * qy - oy * qx + oz * w);
        for (int l = 0; l < kLanes; ++l)
            scalar[l] = handOver[l] != 0;
    }
    // One loop per operation, so that each runs in the lanes.
    for (int k = 0; k < 4; ++k)
        for (int l = 0; l < kLanes; ++l)
            q[k][l] += dq[k][l];
    double norm[kLanes];
    for (int l = 0; l < kLanes; ++l)
        norm[l] = q[0][l] * q[0][l] + q[1][l] * q[1][l] + q[2][l] * q[2][l] + q[3][l] * q[3][l];
    for (int l = 0; l < kLanes; ++l)
        norm[l] = 1.0 / std::sqrt(norm[l]);
    for (int k = 0; k < 4; ++k)
        for (int l = 0; l < kLanes; ++l)
            q[k][l] *= norm[l];
    for (int l = 0; l < kLanes; ++l) {
        const double w = q[0][l], qx = q[1][l], qy = q[2][l], qz = q[3][l];
        rot[0][0][l] = 1 - 2 * (qy * qy + qz * qz), rot[0][1][l] = 2 * (qx * qy - w * qz),
        rot[0][2][l] = 2 * (qx * qz + w * qy);
        rot[1][0][l] = 2 * (qx * qy + w * qz), rot[1][1][l] = 1 - 2 * (qx * qx + qz * qz),
        rot[1][2][l] = 2 * (qy * qz - w * qx);
        rot[2][0][l] = 2 * (qx * qz - w * qy), rot[2][1][l] = 2 * (qy * qz + w * qx),
        rot[2][2][l] = 1 - 2 * (qx * qx + qy * qy);
    }
    for (int l = 0; l < lanes; ++l) {
        const uint32_t e = first + static_cast<uint32_t>(l);
        if (!scalar[l]) {
            if (dq[0][l] != 0.0 || dq[1][l] != 0.0 || dq[2][l] != 0.0 || dq[3][l] != 0.0)
                arrays.rotations[e] = Quat(q[0][l], q[1][l], q[2][l], q[3][l]);
            continue;
        }
        // The rare lane: the whole extraction from its warm start, as the scalar sweep does it.
        Mat3 matrix;
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c)
                matrix(r, c) = a[r][c][l];
        const Mat3 r = extractRotation(matrix, scale2[l], arrays.rotations[e]);
        for (int i = 0; i < 3; ++i)
            for (int k = 0; k < 3; ++k)
                rot[i][k][l] = r(i, k);
    }

    // Deviations d_j = x_j − c − R q_j, C and the update (Eq. 4, shape_matching.h).
    double centre[3][kLanes] = {};
    for (int r = 0; r < 3; ++r)
        for (int j = 0; j < 8; ++j)
            for (int l = 0; l < kLanes; ++l)
                centre[r][l] += 0.125 * x[r][j][l];
    double d[3][8][kLanes];
    for (int r = 0; r < 3; ++r)
        for (int j = 0; j < 8; ++j)
            for (int l = 0; l < kLanes; ++l)
                d[r][j][l] =
                    x[r][j][l] - centre[r][l] -
                    (rot[r][0][l] * batch.rest[0][j][l] + rot[r][1][l] * batch.rest[1][j][l] +
                     rot[r][2][l] * batch.rest[2][j][l]);
    double sum[kLanes] = {}, weighted[kLanes] = {};
    for (int j = 0; j < 8; ++j)
        for (int l = 0; l < kLanes; ++l) {
            const double squared =
                d[0][j][l] * d[0][j][l] + d[1][j][l] * d[1][j][l] + d[2][j][l] * d[2][j][l];
            sum[l] += squared;
            weighted[l] += batch.invMass[j][l] * squared;  // Σ w_j |∇_j C|² = weighted / (64 C²)
        }
    double c[kLanes];
    for (int l = 0; l < kLanes; ++l)
        c[l] = std::sqrt(0.125 * sum[l]);
    double step[kLanes];
    {
        Lanes sumL, weightedL, cL, spread, alphaL, lambdaL;
        load(sumL, sum), load(weightedL, weighted), load(cL, c), load(spread, scale2);
        load(alphaL, alphaTilde), load(lambdaL, lambda);
        // C ≤ 1e-12 ℓ (C² ≤ 1e-24 ℓ²): already at the goal.
        const auto active = (sumL > 8e-24 * spread) & (weightedL > 0.0);
        const Lanes zero = {}, one = zero + 1.0;
        const Lanes cc = active ? cL : one;
        const Lanes denominator = weightedL / (64.0 * cc * cc) + alphaL;
        const Lanes solved = (-cc - alphaL * lambdaL) / denominator;  // inf or NaN when inactive
        const Lanes deltaLambda = active ? solved : zero;
        store(lambda, lambdaL + deltaLambda);
        store(step, deltaLambda / (8.0 * cc));
    }
    for (int r = 0; r < 3; ++r)
        for (int j = 0; j < 8; ++j)
            for (int l = 0; l < kLanes; ++l)
                x[r][j][l] += step[l] * batch.invMass[j][l] * d[r][j][l];

    for (int l = 0; l < lanes; ++l) {
        const uint32_t e = first + static_cast<uint32_t>(l);
        arrays.lambda[e] = lambda[l];
        const HexElement& element = arrays.elements[e];
        std::array<Vec3, 8> corners;
        for (int j = 0; j < 8; ++j)
            corners[j] = Vec3(x[0][j][l], x[1][j][l], x[2][j][l]);
        if (arrays.volumeCompliance[e] >= 0.0) {
            // The optional volume constraint, after the element's shape matching.
            std::array<Vec3, 8> gradient;
            const double cv = volumeError(corners, arrays.volumeGradients[e], gradient);
            double wv = 0.0;
            for (int j = 0; j < 8; ++j)
                wv += arrays.invMass[element[j]] * gradient[j].squaredNorm();
            const double alphaV = arrays.volumeCompliance[e] * invH2;
            if (wv + alphaV > 1e-30 && std::isfinite(cv)) {
                const double deltaLambda = (-cv - alphaV * arrays.volumeLambda[e]) / (wv + alphaV);
                arrays.volumeLambda[e] += deltaLambda;
                for (int j = 0; j < 8; ++j)
                    corners[j] += (arrays.invMass[element[j]] * deltaLambda) * gradient[j];
            }
        }
        for (int j = 0; j < 8; ++j)
            arrays.positions[element[j]] = corners[j];
    }
}

}  // namespace

std::vector<uint32_t> elementWaves(std::span<const HexElement> elements, size_t particleCount) {
    std::vector<uint32_t> next(particleCount, 0);  // per particle: the first wave free of it
    std::vector<uint32_t> wave(elements.size(), 0);
    for (size_t e = 0; e < elements.size(); ++e) {
        uint32_t w = 0;
        for (uint32_t p : elements[e])
            w = std::max(w, next[p]);
        wave[e] = w;
        for (uint32_t p : elements[e])
            next[p] = w + 1;
    }
    return wave;
}

void appendBatches(const ElementArrays& arrays, std::span<const uint32_t> wave, uint32_t first,
                   uint32_t count, std::vector<ElementBatch>& batches) {
    const uint32_t end = first + count;
    const auto shares = [&](uint32_t e, uint32_t from, uint32_t to) {
        for (uint32_t other = from; other < to; ++other)
            for (uint32_t p : arrays.elements[e])
                for (uint32_t o : arrays.elements[other])
                    if (p == o) return true;
        return false;
    };
    for (uint32_t e = first; e < end;) {
        ElementBatch batch{};
        batch.firstElement = e;
        batch.lanes = 1;
        while (batch.lanes < kLanes && e + batch.lanes < end &&
               wave[e + batch.lanes - first] == wave[e - first] &&
               !shares(e + batch.lanes, e, e + batch.lanes))
            ++batch.lanes;
        for (int l = 0; l < kLanes; ++l) {
            const uint32_t element =
                e + static_cast<uint32_t>(l < static_cast<int>(batch.lanes) ? l : 0);
            for (int j = 0; j < 8; ++j) {
                for (int r = 0; r < 3; ++r)
                    batch.rest[r][j][l] = arrays.restOffsets[element][j][r];
                batch.invMass[j][l] = arrays.invMass[arrays.elements[element][j]];
            }
        }
        batches.push_back(batch);
        e += batch.lanes;
    }
}

[[gnu::target_clones("arch=x86-64-v3", "default")]] void solveElementBatches(
    std::span<const ElementBatch> batches, const ElementArrays& arrays, double invH2) {
    for (const ElementBatch& batch : batches)
        solveBatch(batch, arrays, invH2);
}

}  // namespace substep
