// Tests engine/physics/soft/element_batch.cpp: elements of one wave share no particle and every
// element's wave is later than those of the earlier elements it touches, and a sweep of batches
// gives what projecting the elements one after the other in the lattice's order with the scalar
// functions of shape_matching.h gives, on deformed, turned and flat elements, rigid and soft,
// with and without the volume constraint, through the contiguous loads (a tyre's batches) and the gathers,
// and a rolling wheel's turns per substep taken in the lanes (one Newton step) with its result;
// corners held by contacts take no correction into them and hand that push to the contacts.
#include "physics/soft/element_batch.h"
#include "physics/soft/shape_matching.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <map>
#include <string>

namespace substep {
namespace {

/// Every lattice the builders make, with an odd count around for the tyre.
std::vector<Lattice> lattices() {
    return {buildBoxLattice(Vec3(0.3, 0.2, 0.4), {3, 2, 4}),
            buildBoxLattice(Vec3(1, 1, 1), {5, 5, 5}),
            buildBoxLattice(Vec3(1, 1, 1), {1, 1, 1}),
            buildTyreLattice(0.3, 0.2, 0.15, {44, 5, 5}),
            buildTyreLattice(0.3, 0.2, 0.15, {7, 2, 3}),
            buildTyreLattice(0.3, 0.1, 0.1, {3, 1, 1})};
}

TEST(ElementBatch, WavesKeepTheLatticesOrderAndSeparateTheirElements) {
    for (const Lattice& lattice : lattices()) {
        const std::vector<uint32_t> wave = elementWaves(lattice.elements, lattice.positions.size());
        std::vector<std::vector<size_t>> holders(
            lattice.positions.size());  // elements per particle
        for (size_t e = 0; e < lattice.elements.size(); ++e)
            for (uint32_t p : lattice.elements[e])
                holders[p].push_back(e);
        for (const std::vector<size_t>& elements : holders)
            for (size_t a = 0; a < elements.size(); ++a)
                for (size_t b = a + 1; b < elements.size(); ++b)  // elements[a] < elements[b]
                    EXPECT_LT(wave[elements[a]], wave[elements[b]])
                        << elements[a] << " " << elements[b];
        // Far fewer waves than elements: the lanes have work side by side.
        const uint32_t waves = *std::max_element(wave.begin(), wave.end()) + 1;
        if (lattice.elements.size() >= 64) {
            EXPECT_LT(4 * waves, lattice.elements.size());
        }
    }
}

/// A lattice's elements with their rest data, in the lattice's order or wave by wave as
/// SoftSystem keeps them.
struct Elements {
    std::vector<Vec3> x;
    std::vector<HexElement> elements;
    std::vector<uint32_t> wave;
    std::vector<std::array<Vec3, 8>> rest, volumeGradients;
    std::vector<Quat> rotations;
    std::vector<double> scale2, compliance, volumeCompliance, lambda, volumeLambda, invMass;
    std::vector<BatchShape> shapes;  ///< appendBatches' (batch(), below)

    /// `oneCompliance`: every element's compliance the same, as a soft body's (else rigid and soft
    /// in runs, below).
    Elements(const Lattice& lattice, bool byWave, bool someKeepVolume = true, bool oneCompliance = false)
        : x(lattice.positions) {
        const std::vector<uint32_t> waves = elementWaves(lattice.elements, x.size());
        std::vector<size_t> order(lattice.elements.size());
        for (size_t k = 0; k < order.size(); ++k)
            order[k] = k;
        if (byWave)
            std::stable_sort(order.begin(), order.end(),
                             [&](size_t a, size_t b) { return waves[a] < waves[b]; });
        for (size_t i = 0; i < x.size(); ++i)
            invMass.push_back(1.0 + 0.37 * double(i % 5));  // uneven masses
        // As SoftSystem keeps them: each element's rest offsets its shape's, its rotation the
        // shape's turn to it.
        const std::vector<std::array<Vec3, 8>> restOfShape = restShapes(lattice);
        for (const size_t k : order) {
            const HexElement& e = lattice.elements[k];
            elements.push_back(e);
            wave.push_back(waves[k]);
            Vec3 centre = Vec3::Zero();
            for (uint32_t p : e)
                centre += 0.125 * x[p];
            std::array<Vec3, 8> b;
            Mat3 aqq = Mat3::Zero();
            for (int j = 0; j < 8; ++j)
                aqq += 0.125 * (x[e[j]] - centre) * (x[e[j]] - centre).transpose();
            for (int j = 0; j < 8; ++j)
                b[j] = 0.125 * (aqq.inverse() * (x[e[j]] - centre));
            const std::array<Vec3, 8>& q = restOfShape[lattice.shape[k]];
            double l2 = 0.0;
            for (int j = 0; j < 8; ++j)
                l2 += 0.125 * q[j].squaredNorm();
            rest.push_back(q);
            volumeGradients.push_back(b);
            rotations.push_back(lattice.shapeTurn[k]);
            scale2.push_back(l2);
            // Rigid and soft, in runs of 16 elements of the lattice's order: most batches have one
            // shape, some two or more (gathered lane by lane).
            const size_t softness = (k / 16 + lattice.shape[k]) % 3;
            compliance.push_back(oneCompliance ? 1e-7 : softness == 0 ? 0.0 : 1e-7 * double(softness));
            volumeCompliance.push_back(someKeepVolume && k % 4 == 1 ? 1e-6 : -1.0);
            lambda.push_back(0.0);
            volumeLambda.push_back(0.0);
        }
    }

    /// Particles held by a contact (zero: free), what they were pushed with, and the batches
    /// with a held corner.
    std::vector<Vec3> holdNormals;
    std::vector<double> heldImpulse;
    std::vector<uint8_t> heldBatches;

    ElementArrays arrays() {
        ElementArrays a{x,          elements,         rest,   volumeGradients, rotations, scale2,
                        compliance, volumeCompliance, lambda, volumeLambda,    invMass};
        a.holdNormals = holdNormals, a.heldImpulse = heldImpulse, a.heldBatches = heldBatches;
        a.shapes = shapes;
        return a;
    }

    /// The batches of elements [first, first + count), their shapes kept in `shapes`.
    std::vector<ElementBatch> batch(uint32_t first = 0, uint32_t count = UINT32_MAX) {
        count = std::min<uint32_t>(count, static_cast<uint32_t>(elements.size()) - first);
        std::vector<ElementBatch> batches;
        appendBatches(arrays(), std::span(wave).subspan(first), first, count, batches, shapes);
        return batches;
    }
};

/// Marks each batch with a held corner (ElementArrays::heldBatches), as SoftSystem does for the
/// particles in contact.
void markHeldBatches(Elements& s, std::span<const ElementBatch> batches) {
    s.heldBatches.clear();
    for (const ElementBatch& batch : batches) {
        bool any = false;
        for (uint32_t l = 0; l < batch.lanes; ++l)
            for (int j = 0; j < 8; ++j) any = any || !s.holdNormals[batch.particle[j][l]].isZero(0.0);
        s.heldBatches.push_back(any ? 1 : 0);
    }
}

/// Element e's share of a held corner's push into its contact: where the correction
/// Δx_j = w_j ∇_j C Δλ points into it (Δλ's sign is that of `numerator`), the corner's inverse
/// mass along n is 0. Takes the normal part out of `gradient` and returns it (0: not held).
double blockHeld(const Elements& s, uint32_t particle, double numerator, Vec3& gradient) {
    if (s.holdNormals.empty()) return 0.0;
    const Vec3& n = s.holdNormals[particle];
    const double along = n.dot(gradient);
    if (!(numerator * along < 0.0)) return 0.0;
    gradient -= along * n;
    return along;
}

/// The scalar sweep: each element after the other with projectionRotation, Eq. 4 on the
/// shape-matching error, then the volume constraint.
void scalarSweep(Elements& s, double invH2) {
    for (size_t e = 0; e < s.elements.size(); ++e) {
        std::array<Vec3, 8> x, d;
        for (int j = 0; j < 8; ++j)
            x[j] = s.x[s.elements[e][j]];
        const Mat3 r = projectionRotation(shapeMatrix(x, s.rest[e]), s.scale2[e], s.rotations[e]);
        const double c = shapeMatchingError(x, s.rest[e], r, d);
        const double alpha = s.compliance[e] * invH2;
        std::array<double, 8> blocked{};
        for (int j = 0; j < 8; ++j)
            blocked[j] = blockHeld(s, s.elements[e][j], -c - alpha * s.lambda[e], d[j]);
        double weighted = 0.0;
        for (int j = 0; j < 8; ++j)
            weighted += s.invMass[s.elements[e][j]] * d[j].squaredNorm();
        if (c > 1e-12 * std::sqrt(s.scale2[e]) && weighted > 0.0) {
            const double deltaLambda =
                (-c - alpha * s.lambda[e]) / (weighted / (64 * c * c) + alpha);
            s.lambda[e] += deltaLambda;
            for (int j = 0; j < 8; ++j) {
                x[j] += s.invMass[s.elements[e][j]] * deltaLambda / (8 * c) * d[j];
                if (blocked[j] != 0.0) s.heldImpulse[s.elements[e][j]] -= deltaLambda / (8 * c) * blocked[j];
            }
        }
        if (s.volumeCompliance[e] >= 0.0) {
            std::array<Vec3, 8> g;
            const double cv = volumeError(x, s.volumeGradients[e], g);
            const double alphaV = s.volumeCompliance[e] * invH2;
            for (int j = 0; j < 8; ++j)
                blocked[j] = blockHeld(s, s.elements[e][j], -cv - alphaV * s.volumeLambda[e], g[j]);
            double w = 0.0;
            for (int j = 0; j < 8; ++j)
                w += s.invMass[s.elements[e][j]] * g[j].squaredNorm();
            const double deltaLambda = (-cv - alphaV * s.volumeLambda[e]) / (w + alphaV);
            s.volumeLambda[e] += deltaLambda;
            for (int j = 0; j < 8; ++j) {
                x[j] += s.invMass[s.elements[e][j]] * deltaLambda * g[j];
                if (blocked[j] != 0.0) s.heldImpulse[s.elements[e][j]] -= deltaLambda * blocked[j];
            }
        }
        for (int j = 0; j < 8; ++j)
            s.x[s.elements[e][j]] = x[j];
    }
}

/// Deforms the lattice, runs five sweeps of batches and of the scalar functions, and checks
/// that they agree and moved the particles; returns the share of contiguous batches.
double expectBatchesProjectLikeTheScalarSweep(const Lattice& lattice, bool someKeepVolume) {
    const double invH2 = 1200.0 * 1200.0;
    {
        Elements batched(lattice, true, someKeepVolume);
        Elements scalar(lattice, false, someKeepVolume);
        // Deform: a turn of 0.3 rad (beyond one Newton step) on a sheared, squashed lattice,
        // a wobble per particle, and one element flattened to a plane.
        const Mat3 turn =
            Quat(Eigen::AngleAxisd(0.3, Vec3(1, 2, 3).normalized())).toRotationMatrix();
        Mat3 stretch;
        stretch << 1.1, 0.2, 0.0, 0.0, 0.7, 0.1, 0.05, 0.0, 1.0;
        for (size_t i = 0; i < batched.x.size(); ++i) {
            const double k = double(i);
            batched.x[i] = turn * stretch * batched.x[i] +
                           0.01 * Vec3(std::sin(k), std::cos(3 * k), std::sin(7 * k));
        }
        for (uint32_t p : lattice.elements[0])
            batched.x[p].y() = 0.0;
        scalar.x = batched.x;
        const std::vector<ElementBatch> batches = batched.batch();
        const std::vector<Vec3> start = batched.x;
        double size = 0.0;
        for (const Vec3& p : batched.x)
            size = std::max(size, p.norm());
        for (int sweep = 0; sweep < 5; ++sweep) {  // the first turns far, later ones warm-started
            solveElementBatches(batches, batched.arrays(), invH2);
            scalarSweep(scalar, invH2);
        }
        double largest = 0.0;
        for (size_t i = 0; i < batched.x.size(); ++i) {
            EXPECT_TRUE(batched.x[i].allFinite());
            largest = std::max(largest, (batched.x[i] - scalar.x[i]).norm());
        }
        EXPECT_LT(largest, 1e-9 * size) << lattice.elements.size() << " elements";
        // The sweeps moved the particles by far more than the tolerance.
        double moved = 0.0;
        for (size_t i = 0; i < start.size(); ++i)
            moved = std::max(moved, (batched.x[i] - start[i]).norm());
        EXPECT_GT(moved, 1e-3 * size);
        const auto contiguous = std::count_if(batches.begin(), batches.end(),
                                              [](const ElementBatch& b) { return b.contiguous; });
        return double(contiguous) / double(batches.size());
    }
}

TEST(ElementBatch, BatchesProjectLikeOneElementAfterTheOther) {
    for (const Lattice& lattice : lattices())
        expectBatchesProjectLikeTheScalarSweep(lattice, true);
}

TEST(ElementBatch, ContiguousBatchesProjectLikeOneElementAfterTheOther) {
    // Without volume constraints, a tyre's batches of four load their corners as rows (the
    // lattice stores each ring's even cells' particles, then the odd ones'); they must give
    // the scalar sweep's result too.
    for (const Lattice& lattice : lattices())
        expectBatchesProjectLikeTheScalarSweep(lattice, false);
    // The car's tyre: all but the batches at the ends of a ring (22 cells of a parity per
    // ring: five batches of four and one of two shared with the next ring) are contiguous.
    const double share =
        expectBatchesProjectLikeTheScalarSweep(buildTyreLattice(0.3, 0.2, 0.15, {44, 5, 5}), false);
    EXPECT_GT(share, 0.75);
    // Any tyre with more than eight cells around has some.
    EXPECT_GT(expectBatchesProjectLikeTheScalarSweep(buildTyreLattice(0.3, 0.2, 0.1, {9, 2, 1}), false), 0.0);
}

TEST(ElementBatch, TurnsOfARollingWheelStayInTheLanes) {
    // A rolling wheel's elements turn about ω h = 20 rad/s x 0.83 ms = 0.017 rad per substep
    // beyond their warm start. Elements stretched without a turn (their polar rotation the
    // identity, the warm start) and then turned by 0.005 to 0.05 rad: the lanes take all but a
    // few of them in their one Newton step (projectionRotation's), with the scalar sweep's
    // result, its integrateRotation series to the third term and its norm's square root
    // included; turned by 0.3 rad (beyond 0.1) they go to extractRotation, with the same result.
    const Mat3 axes = Quat(Eigen::AngleAxisd(0.7, Vec3(1, -1, 2).normalized())).toRotationMatrix();
    const Mat3 stretch = axes * Vec3(1.02, 0.98, 1.0).asDiagonal() * axes.transpose();  // symmetric
    for (const Lattice& lattice : {buildTyreLattice(0.3, 0.2, 0.15, {44, 5, 5}), buildBoxLattice(Vec3(0.3, 0.2, 0.4), {3, 2, 4})}) {
        for (const double angle : {0.005, 0.017, 0.05, 0.3}) {
            Elements batched(lattice, true, false);
            Elements scalar(lattice, false, false);
            const Mat3 turn = Quat(Eigen::AngleAxisd(angle, Vec3(2, 1, -1).normalized())).toRotationMatrix();
            double size = 0.0;
            for (Vec3& p : batched.x) {
                p = turn * stretch * p;
                size = std::max(size, p.norm());
            }
            scalar.x = batched.x;
            const std::vector<ElementBatch> batches = batched.batch();
            const double invH2 = 1200.0 * 1200.0;
            const uint32_t handedOver = solveElementBatches(batches, batched.arrays(), invH2);
            scalarSweep(scalar, invH2);
            if (angle < 0.1) {
                // (The sweep's own corrections turn a few elements further.)
                EXPECT_LE(100 * handedOver, batched.elements.size()) << angle << " rad";
            } else {
                EXPECT_GT(2 * handedOver, batched.elements.size()) << angle << " rad";
            }
            double largest = 0.0;
            for (size_t i = 0; i < batched.x.size(); ++i)
                largest = std::max(largest, (batched.x[i] - scalar.x[i]).norm());
            EXPECT_LT(largest, 1e-12 * size) << angle << " rad";
        }
    }
}

TEST(ElementBatch, HeldCornersTakeNoCorrectionIntoTheirContact) {
    // The bottom layer of each lattice (and a few particles elsewhere) held by contacts with
    // tilted normals, the lattice squashed onto them and turned: the batches (held ones through
    // the kernel's held path) give the scalar sweep's result; no held particle moves into its
    // contact in any sweep; and the momentum the elements gave the particles, Σ m Δx, is what
    // they handed the contacts, Σ heldImpulse n (each element's corrections alone sum to zero).
    const Mat3 turn = Quat(Eigen::AngleAxisd(0.2, Vec3(1, 2, 3).normalized())).toRotationMatrix();
    const Vec3 normals[3] = {Vec3(0.1, 1, 0).normalized(), Vec3(-0.3, 1, 0.2).normalized(), Vec3(0, 0, 1)};
    for (const Lattice& lattice : lattices()) {
        for (const bool volume : {false, true}) {
            Elements batched(lattice, true, volume);
            double lowest = batched.x[0].y(), size = 0.0;
            for (const Vec3& p : batched.x)
                lowest = std::min(lowest, p.y()), size = std::max(size, p.norm());
            batched.holdNormals.assign(batched.x.size(), Vec3::Zero());
            batched.heldImpulse.assign(batched.x.size(), 0.0);
            int held = 0;
            for (size_t i = 0; i < batched.x.size(); ++i) {
                const bool bottom = batched.x[i].y() < lowest + 1e-9;
                if (bottom || i % 11 == 3) batched.holdNormals[i] = normals[i % 3], ++held;
                // Squashed towards the bottom by 15 %, with a wobble, then turned a little.
                Vec3& p = batched.x[i];
                p.y() = lowest + 0.85 * (p.y() - lowest);
                p = turn * p + 0.005 * Vec3(std::sin(double(i)), std::cos(3.0 * i), std::sin(5.0 * i));
            }
            ASSERT_GT(held, 0);
            Elements scalar(lattice, false, volume);
            scalar.x = batched.x, scalar.holdNormals = batched.holdNormals, scalar.heldImpulse = batched.heldImpulse;
            const std::vector<ElementBatch> batches = batched.batch();
            markHeldBatches(batched, batches);
            const double invH2 = 1200.0 * 1200.0;
            double deepest = 0.0, moved = 0.0;
            for (int sweep = 0; sweep < 5; ++sweep) {
                const std::vector<Vec3> before = batched.x;
                solveElementBatches(batches, batched.arrays(), invH2);
                scalarSweep(scalar, invH2);
                for (size_t i = 0; i < before.size(); ++i) {
                    const Vec3 step = batched.x[i] - before[i];
                    moved = std::max(moved, step.norm());
                    deepest = std::min(deepest, batched.holdNormals[i].dot(step));
                }
            }
            const std::string label = std::to_string(lattice.elements.size()) + " elements" + (volume ? ", volume" : "");
            double largest = 0.0, handed = 0.0;
            Vec3 momentum = Vec3::Zero(), impulse = Vec3::Zero();
            const Elements start(lattice, true, volume);
            for (size_t i = 0; i < batched.x.size(); ++i) {
                largest = std::max(largest, (batched.x[i] - scalar.x[i]).norm());
                EXPECT_NEAR(batched.heldImpulse[i], scalar.heldImpulse[i], 1e-9 * size) << label;
                handed += batched.heldImpulse[i];
                impulse += batched.heldImpulse[i] * batched.holdNormals[i];
            }
            // Σ m Δx from the squashed lattice (recomputed from the same deformation).
            for (size_t i = 0; i < batched.x.size(); ++i) {
                Vec3 p = start.x[i];
                p.y() = lowest + 0.85 * (p.y() - lowest);
                p = turn * p + 0.005 * Vec3(std::sin(double(i)), std::cos(3.0 * i), std::sin(5.0 * i));
                momentum += (batched.x[i] - p) / batched.invMass[i];
            }
            EXPECT_LT(largest, 1e-9 * size) << label;
            EXPECT_GT(moved, 1e-3 * size) << label;
            EXPECT_GE(deepest, -1e-12 * size) << label;  // never into a contact
            EXPECT_GT(handed, 0.0) << label;             // the squash pushed them into it
            EXPECT_LT((momentum - impulse).norm(), 1e-9 * std::max(1.0, impulse.norm())) << label;
        }
    }
}

/// Whether a rows batch's description is the one its particles give: each corner's run from
/// lane 0, one stray at most, named with its particle (none: lane 0 and its own).
void expectRowsDescribeTheirLanes(const ElementBatch& batch) {
    ASSERT_TRUE(batch.rows || batch.contiguous);
    for (int j = 0; j < 8; ++j) {
        ASSERT_GE(batch.run[j], 1);
        for (uint32_t l = 0; l < batch.run[j]; ++l) EXPECT_EQ(batch.particle[j][l], batch.particle[j][0] + l);
        if (batch.run[j] == batch.lanes) {
            EXPECT_EQ(batch.strayLane[j], 0);
            EXPECT_EQ(batch.strayParticle[j], batch.particle[j][0]);
            continue;
        }
        EXPECT_NE(batch.particle[j][batch.run[j]], batch.particle[j][0] + batch.run[j]);
        EXPECT_EQ(batch.run[j] + 1u, batch.lanes);  // one stray, the last lane
        EXPECT_EQ(batch.strayLane[j], batch.run[j]);
        EXPECT_EQ(batch.strayParticle[j], batch.particle[j][batch.run[j]]);
    }
}

TEST(ElementBatch, PairedBatchesAreContiguousAndOfOneWave) {
    // The wide sweep projects a batch with its partner ahead where the batch names one: both
    // must load their corners as rows (contiguous, or rows with `rowsPair` on both) and be of
    // one wave (so share no particle with each other or with the batches between them) and of
    // one body; each batch has one partner at most, and partners name each other.
    for (const Lattice& lattice : lattices()) {
        for (const bool volume : {false, true}) {
            Elements s(lattice, true, volume);
            const uint32_t half = static_cast<uint32_t>(s.elements.size() / 2);
            std::vector<ElementBatch> batches = s.batch(0, half);  // two "bodies"
            const size_t firstOfSecond = batches.size();
            uint32_t firstParticleEnd = 0;  // the first body's particles end here
            for (uint32_t e = 0; e < half; ++e)
                for (const uint32_t p : s.elements[e]) firstParticleEnd = std::max(firstParticleEnd, p + 1);
            const std::vector<ElementBatch> second = s.batch(half);
            batches.insert(batches.end(), second.begin(), second.end());
            for (size_t b = 0; b < batches.size(); ++b) {
                const ElementBatch& batch = batches[b];
                EXPECT_TRUE(batch.partnerAhead == 0 || batch.partnerBehind == 0);
                if (batch.partnerBehind != 0) {
                    ASSERT_GE(b, batch.partnerBehind);
                    EXPECT_EQ(batches[b - batch.partnerBehind].partnerAhead, batch.partnerBehind);
                }
                if (batch.partnerAhead == 0) continue;
                const size_t ahead = b + batch.partnerAhead;
                ASSERT_LT(ahead, batches.size());
                EXPECT_EQ(batches[ahead].partnerBehind, batch.partnerAhead);
                EXPECT_EQ(b < firstOfSecond, ahead < firstOfSecond);
                // Rows stay within their body's particles (the second's start after the first's).
                if (batch.rowsPair && b < firstOfSecond) {
                    for (const ElementBatch* rows : {&batch, static_cast<const ElementBatch*>(&batches[ahead])})
                        for (int j = 0; j < 8; ++j) {
                            EXPECT_LE(rows->particle[j][0] + kBatchLanes, firstParticleEnd);
                        }
                }
                EXPECT_EQ(batch.rowsPair, batches[ahead].rowsPair);
                if (batch.rowsPair) {
                    expectRowsDescribeTheirLanes(batch);
                    expectRowsDescribeTheirLanes(batches[ahead]);
                } else {
                    EXPECT_TRUE(batch.contiguous && batches[ahead].contiguous);
                }
                for (size_t between = b; between <= ahead; ++between)
                    EXPECT_EQ(s.wave[batches[between].firstElement], s.wave[batch.firstElement]);
                for (uint32_t k = 0; k < batch.lanes; ++k)
                    for (uint32_t p : s.elements[batch.firstElement + k])
                        for (uint32_t l = 0; l < batches[ahead].lanes; ++l)
                            for (uint32_t q : s.elements[batches[ahead].firstElement + l])
                                EXPECT_NE(p, q);
            }
        }
    }
    // The car's tyre without volume: every contiguous batch but those alone in their wave's
    // count (one ring of 22 cells: five) is paired, over 90 % of them.
    Elements tyre(buildTyreLattice(0.3, 0.2, 0.15, {44, 5, 5}), true, false);
    const std::vector<ElementBatch> batches = tyre.batch();
    size_t contiguous = 0, paired = 0, pairsOfOneShape = 0, pairs = 0;
    for (size_t b = 0; b < batches.size(); ++b) {
        const ElementBatch& batch = batches[b];
        contiguous += batch.contiguous ? 1 : 0, paired += batch.partnerAhead + batch.partnerBehind != 0 ? 1 : 0;
        if (batch.contiguous) {
            EXPECT_TRUE(batch.oneShape);
        }
        if (batch.partnerAhead == 0) continue;
        ++pairs;
        pairsOfOneShape += batch.shape[0] == batches[b + batch.partnerAhead].shape[0] ? 1 : 0;
    }
    EXPECT_GT(10 * paired, 9 * contiguous) << paired << " of " << contiguous;
    // Its shapes: 25 places across and out, each in up to three compliances (Elements), one
    // record each for its 1100 elements; most pairs have one shape in all eight lanes.
    EXPECT_LE(tyre.shapes.size(), 75u);
    EXPECT_GT(2 * pairsOfOneShape, pairs) << pairsOfOneShape << " of " << pairs;
}

TEST(ElementBatch, RingEndsLoadAsRowsInEightLanes) {
    // A tyre's ring (an even count around: the car's 46, 44, and rings of 15 and 7 cells of a
    // parity) has its cells of one parity in runs of four and the rest at the ring's end; a
    // batch stops there (its shape), and the ends load as rows, paired in eight lanes. Where the
    // ring closes, the odd cells' last one has corners that wrap around to the ring's first
    // particles: that lane is a stray. With one compliance as in a soft body: every batch of two
    // or more lanes loads as rows (but at the tyre's last particles, where four rows would run
    // past the arrays), and the sweep gives the four-lane sweep's bits and the scalar sweep's
    // result.
    if (!wideElementLanes()) GTEST_SKIP() << "this CPU has no x86-64-v4: the sweep is four lanes wide";
    const Mat3 turn = Quat(Eigen::AngleAxisd(0.3, Vec3(1, 2, 3).normalized())).toRotationMatrix();
    for (const std::array<int, 3> cells : {std::array{46, 4, 6}, std::array{44, 5, 5}, std::array{30, 3, 2},
                                          std::array{14, 4, 3}}) {
        const std::string label = std::to_string(cells[0]) + " around";
        Elements wide(buildTyreLattice(0.3, 0.2, 0.15, cells), true, false, true);
        for (size_t i = 0; i < wide.x.size(); ++i) {
            const double k = double(i);
            wide.x[i] = turn * wide.x[i] + 0.01 * Vec3(std::sin(k), std::cos(3 * k), std::sin(7 * k));
        }
        const std::vector<ElementBatch> batches = wide.batch();
        size_t strays = 0, rowsBatches = 0;
        std::map<uint32_t, int> unpairedOfWave;  // rows or contiguous batches without a partner
        for (size_t b = 0; b < batches.size(); ++b) {
            const ElementBatch& batch = batches[b];
            if ((batch.rows || batch.contiguous) && batch.partnerAhead + batch.partnerBehind == 0)
                ++unpairedOfWave[wide.wave[batch.firstElement]];
            // (Rows need four rows inside the arrays: not so at the tyre's last particles.)
            bool pastTheEnd = batch.firstElement + kBatchLanes > wide.elements.size();
            for (int j = 0; j < 8; ++j) pastTheEnd = pastTheEnd || batch.particle[j][0] + kBatchLanes > wide.x.size();
            EXPECT_TRUE(batch.contiguous || batch.rows || batch.lanes == 1 || pastTheEnd)
                << label << ", batch " << b << " of " << batches.size() << ", " << batch.lanes << " lanes, runs "
                << int(batch.run[0]) << int(batch.run[1]) << int(batch.run[2]) << int(batch.run[3]) << int(batch.run[4])
                << int(batch.run[5]) << int(batch.run[6]) << int(batch.run[7]) << " one shape " << batch.oneShape;
            rowsBatches += batch.rows ? 1 : 0;
            if (!batch.rowsPair) continue;
            for (int j = 0; j < 8; ++j) strays += batch.run[j] < batch.lanes ? 1 : 0;
        }
        EXPECT_GT(rowsBatches, 0u) << label;
        EXPECT_GT(strays, 0u) << label;  // paired
        // A wave's ring ends pair among themselves and with the contiguous batches left over.
        for (const auto& [wave, unpaired] : unpairedOfWave) {
            EXPECT_LE(unpaired, 1) << label << ", wave " << wave;
        }
        Elements four = wide, scalar(buildTyreLattice(0.3, 0.2, 0.15, cells), false, false, true);
        scalar.x = wide.x;  // the scalar sweep, in the lattice's order: the same particles
        const double invH2 = 1e6;
        for (int sweep = 0; sweep < 5; ++sweep) {
            solveElementBatches(batches, wide.arrays(), invH2, ElementLanes::Widest);
            solveElementBatches(batches, four.arrays(), invH2, ElementLanes::Four);
            scalarSweep(scalar, invH2);
        }
        const auto same = [](const auto& a, const auto& b) {
            return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0;
        };
        EXPECT_TRUE(same(wide.x, four.x)) << label;
        EXPECT_TRUE(same(wide.rotations, four.rotations)) << label;
        EXPECT_TRUE(same(wide.lambda, four.lambda)) << label;
        double largest = 0.0, size = 0.0;
        for (size_t i = 0; i < wide.x.size(); ++i) {
            largest = std::max(largest, (wide.x[i] - scalar.x[i]).norm());
            size = std::max(size, wide.x[i].norm());
        }
        EXPECT_LT(largest, 1e-9 * size) << label;
    }
}

TEST(ElementBatch, EightLanesGiveTheBitsOfFour) {
    // The wide sweep (pairs of batches in one AVX-512 register) and the four-lane one, on every
    // lattice deformed and turned as above, some corners held, five sweeps: the same positions,
    // rotations, multipliers and held impulses, bit for bit.
    if (!wideElementLanes()) GTEST_SKIP() << "this CPU has no x86-64-v4: the sweep is four lanes wide";
    const Mat3 turn = Quat(Eigen::AngleAxisd(0.3, Vec3(1, 2, 3).normalized())).toRotationMatrix();
    for (const Lattice& lattice : lattices()) {
        for (const bool volume : {false, true}) {
            Elements wide(lattice, true, volume);
            for (size_t i = 0; i < wide.x.size(); ++i) {
                const double k = double(i);
                wide.x[i] = turn * wide.x[i] + 0.01 * Vec3(std::sin(k), std::cos(3 * k), std::sin(7 * k));
            }
            wide.holdNormals.assign(wide.x.size(), Vec3::Zero());
            wide.heldImpulse.assign(wide.x.size(), 0.0);
            for (size_t i = 0; i < wide.x.size(); i += 37)
                wide.holdNormals[i] = Vec3(0.1, 1, 0).normalized();
            const std::vector<ElementBatch> batches = wide.batch();
            markHeldBatches(wide, batches);
            Elements four = wide;
            uint32_t handedWide = 0, handedFour = 0;
            for (int sweep = 0; sweep < 5; ++sweep) {
                handedWide += solveElementBatches(batches, wide.arrays(), 1e6, ElementLanes::Widest);
                handedFour += solveElementBatches(batches, four.arrays(), 1e6, ElementLanes::Four);
            }
            const std::string label = std::to_string(lattice.elements.size()) + " elements" + (volume ? ", volume" : "");
            EXPECT_EQ(handedWide, handedFour) << label;
            const auto same = [](const auto& a, const auto& b) {
                return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0;
            };
            EXPECT_TRUE(same(wide.x, four.x)) << label;
            EXPECT_TRUE(same(wide.rotations, four.rotations)) << label;
            EXPECT_TRUE(same(wide.lambda, four.lambda)) << label;
            EXPECT_TRUE(same(wide.volumeLambda, four.volumeLambda)) << label;
            EXPECT_TRUE(same(wide.heldImpulse, four.heldImpulse)) << label;
        }
    }
}

}  // namespace
}  // namespace substep
