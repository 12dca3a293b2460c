// Tests engine/physics/soft/element_damping.cpp: a rigid motion is not damped, a pure
// deformation rate decays by exp(−k dt), the momentum and angular momentum are kept, and the
// batches' lanes give what damping the elements one after the other gives; eight lanes (pairs
// of batches), four lanes and the elements one by one with the lanes' arithmetic give the same
// bits.
#include "physics/soft/element_damping.h"

#include "physics/soft/element_damping_kernel.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>

namespace substep {
namespace {

/// A lattice's elements stored wave by wave, as SoftSystem keeps them, with their batches.
struct Damped {
    std::vector<Vec3> x, v;
    std::vector<double> mass, damping;
    std::vector<HexElement> elements;
    std::vector<ElementBatch> batches;

    Damped(const Lattice& lattice, double rate) : x(lattice.positions), v(x.size(), Vec3::Zero()) {
        const std::vector<uint32_t> waves = elementWaves(lattice.elements, x.size());
        std::vector<size_t> order(lattice.elements.size());
        for (size_t k = 0; k < order.size(); ++k)
            order[k] = k;
        std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return waves[a] < waves[b]; });
        std::vector<uint32_t> wave;
        // The lattice's rest shapes, as SoftSystem gives them: a tyre's batches end with its
        // rings (ElementBatch::rows).
        const std::vector<std::array<Vec3, 8>> shapes = restShapes(lattice);
        std::vector<std::array<Vec3, 8>> rest;
        std::vector<double> scale2(order.size(), 1.0), compliance(order.size(), 0.0);
        std::vector<double> volumeCompliance(order.size(), -1.0), invMass;
        for (size_t i = 0; i < x.size(); ++i) {
            mass.push_back(1.0 + 0.37 * double(i % 5));  // uneven masses
            invMass.push_back(1.0 / mass.back());
        }
        for (const size_t k : order) {
            elements.push_back(lattice.elements[k]);
            rest.push_back(shapes[lattice.shape[k]]);
            wave.push_back(waves[k]);
            damping.push_back(rate);
        }
        ElementArrays arrays{.elements = elements, .restOffsets = rest, .scale2 = scale2,
                             .compliance = compliance, .volumeCompliance = volumeCompliance, .invMass = invMass};
        std::vector<BatchShape> batchShapes;
        appendBatches(arrays, wave, 0, static_cast<uint32_t>(elements.size()), batches, batchShapes);
    }

    DampingArrays arrays() { return {.positions = x, .velocities = v, .mass = mass, .damping = damping}; }
    void damp(double dt, ElementLanes lanes = ElementLanes::Widest) {
        dampElementBatches(batches, arrays(), dt, lanes);
    }

    Vec3 momentum() const {
        Vec3 p = Vec3::Zero();
        for (size_t i = 0; i < v.size(); ++i) p += mass[i] * v[i];
        return p;
    }
    Vec3 angularMomentum() const {
        Vec3 l = Vec3::Zero();
        for (size_t i = 0; i < v.size(); ++i) l += mass[i] * x[i].cross(v[i]);
        return l;
    }
};

/// The elements one after the other: each corner's velocity towards the element's rigid motion.
void scalarDamp(Damped& s, double dt) {
    for (size_t e = 0; e < s.elements.size(); ++e) {
        const double fraction = 1.0 - std::exp(-s.damping[e] * dt);
        double mass = 0.0;
        Vec3 centre = Vec3::Zero(), momentum = Vec3::Zero();
        for (uint32_t i : s.elements[e]) mass += s.mass[i], centre += s.mass[i] * s.x[i], momentum += s.mass[i] * s.v[i];
        centre /= mass;
        const Vec3 velocity = momentum / mass;
        Vec3 l = Vec3::Zero();
        Mat3 inertia = Mat3::Zero();
        for (uint32_t i : s.elements[e]) {
            const Vec3 r = s.x[i] - centre;
            l += s.mass[i] * r.cross(s.v[i] - velocity);
            inertia += s.mass[i] * (r.squaredNorm() * Mat3::Identity() - r * r.transpose());
        }
        const Vec3 omega = inertia.inverse() * l;
        for (uint32_t i : s.elements[e])
            s.v[i] += fraction * (velocity + omega.cross(s.x[i] - centre) - s.v[i]);
    }
}

std::vector<Lattice> lattices() {
    return {buildBoxLattice(Vec3(0.3, 0.2, 0.4), {3, 2, 4}), buildTyreLattice(0.3, 0.2, 0.15, {44, 5, 5}),
            buildTyreLattice(0.3, 0.2, 0.15, {7, 2, 3})};
}

TEST(ElementDamping, RigidMotionIsNotDamped) {
    for (const Lattice& lattice : lattices()) {
        Damped d(lattice, 20.0);
        const Vec3 u(0.3, -1.0, 2.0), omega(4.0, -2.0, 7.0);
        for (size_t i = 0; i < d.x.size(); ++i) d.v[i] = u + omega.cross(d.x[i]);
        const std::vector<Vec3> before = d.v;
        d.damp(1.0 / 60.0);
        double largest = 0.0;
        for (size_t i = 0; i < d.v.size(); ++i) largest = std::max(largest, (d.v[i] - before[i]).norm());
        EXPECT_LT(largest, 1e-12) << lattice.elements.size() << " elements";
    }
}

TEST(ElementDamping, DeformationRateDecaysExponentially) {
    // One cube, equal masses, v = D (x − c) with D symmetric: no spin (Σ m r × D r = 0 for a
    // cube's isotropic second moment) and no mean velocity, so all of it decays: v → e^(−k dt) v.
    for (const double rate : {1.0, 20.0, 300.0}) {
        Damped d(buildBoxLattice(Vec3(0.1, 0.1, 0.1), {1, 1, 1}), rate);
        std::fill(d.mass.begin(), d.mass.end(), 0.5);
        Mat3 strain;
        strain << 0.4, 0.1, -0.2, 0.1, -0.3, 0.05, -0.2, 0.05, 0.7;
        Vec3 centre = Vec3::Zero();
        for (const Vec3& p : d.x) centre += p / 8.0;
        for (size_t i = 0; i < 8; ++i) d.v[i] = strain * (d.x[i] - centre);
        const std::vector<Vec3> before = d.v;
        const double dt = 1.0 / 60.0;
        d.damp(dt);
        for (size_t i = 0; i < 8; ++i)
            EXPECT_LT((d.v[i] - std::exp(-rate * dt) * before[i]).norm(), 1e-13) << rate;
    }
}

TEST(ElementDamping, KeepsMomentaAndMatchesTheElementsOneAfterTheOther) {
    for (const Lattice& lattice : lattices()) {
        Damped d(lattice, 15.0);
        for (size_t i = 0; i < d.x.size(); ++i) {
            const double k = double(i);
            d.v[i] = Vec3(std::sin(k), std::cos(3 * k), std::sin(7 * k)) + Vec3(0.5, 0.0, -1.0);
            d.x[i] += 0.01 * Vec3(std::cos(5 * k), std::sin(2 * k), std::cos(k));  // deformed
        }
        Damped scalar = d;
        const Vec3 momentum = d.momentum(), angular = d.angularMomentum();
        const std::vector<Vec3> before = d.v;
        d.damp(1.0 / 60.0);
        scalarDamp(scalar, 1.0 / 60.0);
        const std::string label = std::to_string(lattice.elements.size()) + " elements";
        double largest = 0.0, changed = 0.0;
        for (size_t i = 0; i < d.v.size(); ++i) {
            largest = std::max(largest, (d.v[i] - scalar.v[i]).norm());
            changed = std::max(changed, (d.v[i] - before[i]).norm());
        }
        EXPECT_LT(largest, 1e-12) << label;
        EXPECT_GT(changed, 0.05) << label;  // it did damp
        EXPECT_LT((d.momentum() - momentum).norm(), 1e-12 * momentum.norm()) << label;
        EXPECT_LT((d.angularMomentum() - angular).norm(), 1e-11 * std::max(1.0, angular.norm())) << label;
    }
}

/// One element damped with the kernel's arithmetic, scalar, operation for operation
/// (element_damping_kernel.h's towardsRigidMotion): the lanes' reference, bit for bit.
[[gnu::always_inline]] inline void dampElementAsTheLanes(Damped& s, uint32_t e, double fraction) {
    double rx[8], ry[8], rz[8], vx[8], vy[8], vz[8], m[8];
    for (int j = 0; j < 8; ++j) {
        const uint32_t i = s.elements[e][j];
        rx[j] = s.x[i].x(), ry[j] = s.x[i].y(), rz[j] = s.x[i].z();
        vx[j] = s.v[i].x(), vy[j] = s.v[i].y(), vz[j] = s.v[i].z();
        m[j] = s.mass[i];
    }
    double mass = 0.0, cx = 0.0, cy = 0.0, cz = 0.0, px = 0.0, py = 0.0, pz = 0.0;
    for (int j = 0; j < 8; ++j) {
        mass += m[j];
        cx += m[j] * rx[j], cy += m[j] * ry[j], cz += m[j] * rz[j];
        px += m[j] * vx[j], py += m[j] * vy[j], pz += m[j] * vz[j];
    }
    cx /= mass, cy /= mass, cz /= mass;
    const double ux = px / mass, uy = py / mass, uz = pz / mass;
    double lx = 0.0, ly = 0.0, lz = 0.0, sxx = 0.0, syy = 0.0, szz = 0.0, sxy = 0.0, sxz = 0.0, syz = 0.0;
    for (int j = 0; j < 8; ++j) {
        rx[j] -= cx, ry[j] -= cy, rz[j] -= cz;
        const double mx = m[j] * rx[j], my = m[j] * ry[j], mz = m[j] * rz[j];
        const double dx = vx[j] - ux, dy = vy[j] - uy, dz = vz[j] - uz;
        lx += my * dz - mz * dy, ly += mz * dx - mx * dz, lz += mx * dy - my * dx;
        sxx += mx * rx[j], syy += my * ry[j], szz += mz * rz[j];
        sxy += mx * ry[j], sxz += mx * rz[j], syz += my * rz[j];
    }
    const double spread = sxx + syy + szz;
    const double i00 = spread - sxx, i11 = spread - syy, i22 = spread - szz;
    const double i01 = -sxy, i02 = -sxz, i12 = -syz;
    const double a00 = i11 * i22 - i12 * i12, a01 = i02 * i12 - i01 * i22, a02 = i01 * i12 - i02 * i11;
    const double a11 = i00 * i22 - i02 * i02, a12 = i01 * i02 - i00 * i12, a22 = i00 * i11 - i01 * i01;
    const double det = i00 * a00 + i01 * a01 + i02 * a02;
    const double trace = i00 + i11 + i22;
    const bool spins = (det < 0 ? -det : det) > 1e-9 * trace * trace * trace;
    const double wx = spins ? (a00 * lx + a01 * ly + a02 * lz) / det : 0.0;
    const double wy = spins ? (a01 * lx + a11 * ly + a12 * lz) / det : 0.0;
    const double wz = spins ? (a02 * lx + a12 * ly + a22 * lz) / det : 0.0;
    for (int j = 0; j < 8; ++j) {
        vx[j] += fraction * (ux + (wy * rz[j] - wz * ry[j]) - vx[j]);
        vy[j] += fraction * (uy + (wz * rx[j] - wx * rz[j]) - vy[j]);
        vz[j] += fraction * (uz + (wx * ry[j] - wy * rx[j]) - vz[j]);
        s.v[s.elements[e][j]] = Vec3(vx[j], vy[j], vz[j]);
    }
}

/// The elements one after the other with the lanes' arithmetic: a batch with no damped lane is
/// left alone, its other lanes take fraction 0 (which turns −0 into +0).
void dampAsTheLanes(Damped& s, double dt) {
    for (const ElementBatch& batch : s.batches) {
        bool any = false;
        for (uint32_t l = 0; l < batch.lanes; ++l) any = any || s.damping[batch.firstElement + l] > 0.0;
        if (!any) continue;
        for (uint32_t l = 0; l < batch.lanes; ++l) {
            const double k = s.damping[batch.firstElement + l];
            dampElementAsTheLanes(s, batch.firstElement + l, k > 0.0 ? 1.0 - std::exp(-k * dt) : 0.0);
        }
    }
}

/// The four lanes' kernel built for this file's target, the base ISA: no FMA to fuse products
/// and sums into, as in the scalar reference (the engine's x86-64-v3 and -v4 builds fuse them,
/// in four lanes and eight alike, and differ from it by rounding).
void dampFourLanesWithoutFma(Damped& s, double dt) {
    DampingFractions fractions{.dt = dt};
    const DampingArrays arrays = s.arrays();
    for (const ElementBatch& batch : s.batches) {
        simd::Lanes fraction;
        if (fractions.of(batch, s.damping, fraction)) DampingKernel<simd::Lanes>::dampOne(batch, arrays, fraction);
    }
}

/// Bit for bit, NaN matching any NaN (its sign and payload are the hardware's choice).
bool sameBits(const std::vector<Vec3>& a, const std::vector<Vec3>& b, std::string& first) {
    for (size_t i = 0; i < a.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            const double p = a[i][c], q = b[i][c];
            if ((std::isnan(p) && std::isnan(q)) || std::memcmp(&p, &q, sizeof p) == 0) continue;
            first = "particle " + std::to_string(i) + " axis " + std::to_string(c) + ": " + std::to_string(p) +
                    " vs " + std::to_string(q);
            return false;
        }
    return true;
}

/// Within rounding: every component within 1e-12 (1 + its size) of the other, NaN where it is.
bool withinRounding(const std::vector<Vec3>& a, const std::vector<Vec3>& b, std::string& first) {
    for (size_t i = 0; i < a.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            const double p = a[i][c], q = b[i][c];
            if ((std::isnan(p) && std::isnan(q)) || std::abs(p - q) <= 1e-12 * (1.0 + std::abs(q))) continue;
            first = "particle " + std::to_string(i) + " axis " + std::to_string(c) + ": " + std::to_string(p) +
                    " vs " + std::to_string(q);
            return false;
        }
    return true;
}

/// The lattices of the lanes' test: the RC car's tyre (rc_car.h: 46 x 4 x 6), rings of 14, 30
/// and 44 cells (ring ends of every kind: three cells, odd, even), an odd ring and boxes.
std::vector<Lattice> laneLattices() {
    return {buildTyreLattice(0.07, 0.05, 0.06, {46, 4, 6}), buildTyreLattice(0.3, 0.2, 0.15, {14, 2, 3}),
            buildTyreLattice(0.3, 0.2, 0.15, {30, 3, 2}),   buildTyreLattice(0.3, 0.2, 0.15, {44, 5, 5}),
            buildTyreLattice(0.3, 0.2, 0.15, {7, 2, 3}),    buildBoxLattice(Vec3(0.3, 0.2, 0.4), {3, 2, 4}),
            buildBoxLattice(Vec3(0.5, 0.4, 0.3), {9, 5, 4}), buildBoxLattice(Vec3(0.1, 0.1, 0.1), {1, 1, 1})};
}

/// Random velocities and a deformed lattice, and per element a rate of 0, −1 (left alone) or one
/// of three: `variant` 1 adds ±0 velocity components and stretches of undamped elements (whole
/// batches, some paired with damped ones), 2 a NaN velocity and a collapsed element.
void randomise(Damped& d, unsigned seed, int variant) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    for (size_t i = 0; i < d.x.size(); ++i) {
        d.v[i] = Vec3(unit(random), unit(random), unit(random)) * (1.0 + 3.0 * std::abs(unit(random)));
        d.x[i] += 0.004 * Vec3(unit(random), unit(random), unit(random));
        d.mass[i] = 0.5 + std::abs(unit(random));
    }
    const double rates[] = {0.0, -1.0, 8.0, 20.0, 20.0, 20.0, 150.0};
    std::uniform_int_distribution<int> pick(0, 6);
    for (double& k : d.damping) k = rates[pick(random)];
    if (variant == 1) {
        for (size_t i = 0; i < d.v.size(); i += 3) d.v[i][i % 3] = (i % 2 == 0) ? -0.0 : 0.0;
        for (size_t i = 1; i < d.v.size(); i += 7) d.v[i] = Vec3(-0.0, -0.0, -0.0);
        // Every third stretch of 12 elements undamped.
        for (size_t e = 0; e < d.damping.size(); ++e)
            if (e / 12 % 3 == 1) d.damping[e] = (e % 2 == 0) ? 0.0 : -2.0;
    }
    if (variant == 2) {
        d.v[d.v.size() / 2].y() = std::numeric_limits<double>::quiet_NaN();
        const HexElement& collapsed = d.elements[d.elements.size() / 3];
        for (const uint32_t i : collapsed) d.x[i] = d.x[collapsed[0]];
    }
}

TEST(ElementDamping, EightLanesFourLanesAndTheScalarElementsGiveTheSameBits) {
    // Eight lanes (pairs of batches) against four, bit for bit, each built as the engine builds
    // it (x86-64-v4 on this CPU where it has AVX-512); the four lanes built without FMA against
    // the elements one by one with the lanes' arithmetic, bit for bit; and the engine's four
    // lanes against those within rounding (they fuse products and sums).
    int rowsPairs = 0, strayPairs = 0, pairs = 0;
    for (const Lattice& lattice : laneLattices()) {
        for (int variant = 0; variant < 3; ++variant) {
            for (unsigned seed = 1; seed <= 4; ++seed) {
                Damped d(lattice, 0.0);
                randomise(d, seed * 7919u + static_cast<unsigned>(lattice.elements.size()), variant);
                Damped four = d, eight = d, plain = d, scalar = d;
                const double dt = 1.0 / 60.0;
                const std::string label = std::to_string(lattice.elements.size()) + " elements, variant " +
                                          std::to_string(variant) + ", seed " + std::to_string(seed);
                // Twice: the second pass starts from the first's velocities.
                for (int pass = 0; pass < 2; ++pass) {
                    four.damp(dt, ElementLanes::Four);
                    if (wideElementLanes()) dampElementBatchesWide(eight.batches, eight.arrays(), dt);
                    else eight.damp(dt);
                    dampFourLanesWithoutFma(plain, dt);
                    dampAsTheLanes(scalar, dt);
                    const std::string at = "pass " + std::to_string(pass) + ", " + label + ": ";
                    std::string where;
                    EXPECT_TRUE(sameBits(eight.v, four.v, where)) << "eight lanes, " << at << where;
                    EXPECT_TRUE(sameBits(plain.v, scalar.v, where)) << "four lanes without FMA, " << at << where;
                    EXPECT_TRUE(withinRounding(four.v, scalar.v, where)) << "four lanes, " << at << where;
                    EXPECT_TRUE(sameBits(d.x, four.x, where) && sameBits(d.x, eight.x, where)) << "positions kept";
                }
                if (lattice.elements.size() > 1) {
                    EXPECT_FALSE(d.v == eight.v) << label;  // it did damp
                }
            }
        }
        Damped d(lattice, 1.0);
        for (const ElementBatch& batch : d.batches) {
            if (batch.partnerAhead == 0) continue;
            ++pairs;
            rowsPairs += batch.rowsPair;
            const size_t b = static_cast<size_t>(&batch - d.batches.data());
            const ElementBatch& partner = d.batches[b + batch.partnerAhead];
            strayPairs += batch.rowsPair && (batch.strayCorners | partner.strayCorners) != 0;
        }
    }
    // The eight lanes met each kind of pair: contiguous, rows, rows with strays.
    EXPECT_GT(pairs, 100);
    EXPECT_GT(rowsPairs, 10);
    EXPECT_GT(strayPairs, 5);
}

TEST(ElementDamping, NoBatchesDampNothing) {
    Damped d(buildBoxLattice(Vec3(0.1, 0.1, 0.1), {1, 1, 1}), 10.0);
    d.v[0] = Vec3(1.0, 2.0, 3.0);
    const std::vector<Vec3> before = d.v;
    dampElementBatches({}, d.arrays(), 1.0 / 60.0);
    if (wideElementLanes()) dampElementBatchesWide({}, d.arrays(), 1.0 / 60.0);
    EXPECT_EQ(before, d.v);
}

}  // namespace
}  // namespace substep
