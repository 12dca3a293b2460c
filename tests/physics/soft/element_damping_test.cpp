// Tests engine/physics/soft/element_damping.cpp: a rigid motion is not damped, a pure
// deformation rate decays by exp(−k dt), the momentum and angular momentum are kept, and the
// batches' lanes give what damping the elements one after the other gives.
#include "physics/soft/element_damping.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
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
        std::vector<std::array<Vec3, 8>> rest(order.size());
        std::vector<double> scale2(order.size(), 1.0), compliance(order.size(), 0.0);
        std::vector<double> volumeCompliance(order.size(), -1.0), invMass;
        for (size_t i = 0; i < x.size(); ++i) {
            mass.push_back(1.0 + 0.37 * double(i % 5));  // uneven masses
            invMass.push_back(1.0 / mass.back());
        }
        for (const size_t k : order) {
            elements.push_back(lattice.elements[k]);
            wave.push_back(waves[k]);
            damping.push_back(rate);
        }
        ElementArrays arrays{.elements = elements, .restOffsets = rest, .scale2 = scale2,
                             .compliance = compliance, .volumeCompliance = volumeCompliance, .invMass = invMass};
        std::vector<BatchShape> shapes;
        appendBatches(arrays, wave, 0, static_cast<uint32_t>(elements.size()), batches, shapes);
    }

    void damp(double dt) { dampElementBatches(batches, {.positions = x, .velocities = v, .mass = mass, .damping = damping}, dt); }

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

}  // namespace
}  // namespace substep
