// Tests engine/physics/soft/still_contacts.h: groups of still contacts solved in vector lanes
// (still_contact_lanes.cpp's four, still_contact_lanes_wide.cpp's eight) give the bits of the
// same contacts solved one by one in order, in the position solve (Eqs. 26-28, with held
// impulses) and the velocity pass (Eqs. 30, 34): particles, multipliers and friction impulses,
// over random contact lists with runs of every length from 0 to 20 between moving contacts and
// repeated particles, zero friction, pinned particles, NaN and ±0 in velocities, impulses and
// multipliers, the push-out cap on and off.
#include "physics/soft/still_contacts.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

namespace substep {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// A random contact list with its particles.
struct ContactsCase {
    std::vector<ParticleContact> contacts;
    std::vector<Vec3> x, xPrev, v, vPrev;
    std::vector<double> invMass, heldImpulse;
    ContactStep step;

    ContactParticles particles() {
        return {.x = x.data(),
                .xPrev = xPrev.data(),
                .v = v.data(),
                .vPrev = vPrev.data(),
                .invMass = invMass.data(),
                .heldImpulse = heldImpulse.data()};
    }
};

class Random {
  public:
    explicit Random(uint64_t seed) : rng_(seed) {}
    double unit() { return std::uniform_real_distribution<double>(-1.0, 1.0)(rng_); }
    int below(int n) { return std::uniform_int_distribution<int>(0, n - 1)(rng_); }
    bool chance(double p) { return std::uniform_real_distribution<double>(0.0, 1.0)(rng_) < p; }
    /// Mostly ordinary, sometimes ±0 or NaN.
    double awkward(double value) {
        switch (below(24)) {
            case 0:
                return 0.0;
            case 1:
                return -0.0;
            case 2:
                return kNaN;
            default:
                return value;
        }
    }
    Vec3 vector(double scale) { return Vec3(unit(), unit(), unit()) * scale; }
    Vec3 awkwardVector(double scale) {
        return Vec3(awkward(scale * unit()), awkward(scale * unit()), awkward(scale * unit()));
    }
    /// A unit normal, now and then along an axis (its other coordinates ±0).
    Vec3 normal() {
        if (chance(0.2)) {
            Vec3 n(below(2) ? 0.0 : -0.0, below(2) ? 0.0 : -0.0, below(2) ? 0.0 : -0.0);
            n[below(3)] = below(2) ? 1.0 : -1.0;
            return n;
        }
        return vector(1.0).normalized();
    }

  private:
    std::mt19937_64 rng_;
};

ContactsCase randomCase(Random& random) {
    ContactsCase c;
    const int particleCount = 48;
    for (int p = 0; p < particleCount; ++p) {
        c.x.push_back(random.vector(1.0));
        // Some particles did not move (no slip), others moved a little or a lot.
        c.xPrev.push_back(random.chance(0.15)
                              ? c.x.back()
                              : Vec3(c.x.back() + random.vector(random.chance(0.5) ? 1e-4 : 1e-2)));
        c.v.push_back(random.awkwardVector(random.chance(0.5) ? 0.1 : 5.0));
        c.vPrev.push_back(random.awkwardVector(random.chance(0.5) ? 0.01 : 5.0));
        c.invMass.push_back(random.chance(0.05) ? 0.0 : std::exp(3.0 * random.unit()));
        const int held = random.below(6);
        c.heldImpulse.push_back(held == 0   ? 1e-5 * (1.5 + random.unit())
                                : held == 1 ? -1e-5
                                : held == 2 ? kNaN
                                            : 0.0);
    }
    const double h = 1.0 / (60.0 * (1 + random.below(20)));
    c.step = {
        .h = h,
        .capPushOut = random.chance(0.7),
        .gravityStep = Vec3(random.below(2) ? 0.0 : -0.0, -9.81 * h, random.below(2) ? 0.0 : -0.0),
        .restingSpeed = 2.0 * 9.81 * h};
    // Runs of still contacts on distinct particles, of every length from 0 to 20, each ended by
    // a moving contact or a still one on a particle of the run.
    for (int run = 0; run <= 20; ++run) {
        const int length = random.chance(0.8) ? run : random.below(21);
        std::vector<uint32_t> used;
        for (int k = 0; k < length + 1; ++k) {
            ParticleContact contact;
            const bool ends = k == length;
            uint32_t p = static_cast<uint32_t>(random.below(particleCount));
            bool repeated = false;
            for (uint32_t u : used)
                repeated = repeated || u == p;
            if (ends && !used.empty() && random.chance(0.5)) {
                p = used[static_cast<size_t>(random.below(static_cast<int>(used.size())))];
            } else if (!ends && repeated && random.chance(0.9)) {
                continue;  // mostly distinct within the run
            }
            used.push_back(p);
            contact.particle = p;
            contact.body = static_cast<uint32_t>(random.below(4));
            contact.still = !(ends && random.chance(0.5));
            contact.normal = random.normal();
            contact.radius = 0.01 * (1.0 + random.unit() * 0.5);
            // The body's point about the particle's surface point: apart or overlapping, some
            // by more than the cap lets out in one substep.
            const double overlap = random.chance(0.3) ? 0.05 * random.unit() : 1e-3 * random.unit();
            contact.anchor = c.x[p] - contact.radius * contact.normal + overlap * contact.normal +
                             random.vector(0.01);
            contact.staticFriction = random.chance(0.2) ? random.awkward(0.0)
                                                        : random.awkward(0.3 + random.unit() * 0.3);
            contact.dynamicFriction =
                random.chance(0.2) ? 0.0 : random.awkward(0.3 + random.unit() * 0.3);
            contact.restitution = random.chance(0.5) ? 0.0 : 0.5 + 0.5 * random.unit();
            contact.lambdaNormal =
                random.chance(0.3) ? 0.0 : random.awkward(1e-4 * (1.0 + random.unit()));
            contact.lambdaTangent =
                random.chance(0.5) ? 0.0 : random.awkward(1e-5 * (1.0 + random.unit()));
            contact.frictionImpulse =
                random.chance(0.5) ? Vec3::Zero() : random.awkwardVector(1e-5);
            c.contacts.push_back(contact);
        }
    }
    return c;
}

/// A moving body's contact as the tests solve it: changes in an order-dependent way its
/// particle and its held impulse (the lanes must leave it where it was in the list).
void solveMovingPosition(ParticleContact& c, const ContactParticles& particles) {
    c.lambdaNormal += particles.heldImpulse[c.particle] + 1.0;
    particles.heldImpulse[c.particle] = 0.0;
    particles.x[c.particle] = 0.5 * particles.x[c.particle] + 0.25 * c.normal;
}

void solveMovingVelocity(const ParticleContact& c, const ContactParticles& particles) {
    particles.v[c.particle] = 0.75 * particles.v[c.particle] + c.normal;
}

/// The same bits (NaN payloads alike).
bool same(double a, double b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}
bool same(const Vec3& a, const Vec3& b) {
    return same(a.x(), b.x()) && same(a.y(), b.y()) && same(a.z(), b.z());
}

void expectSame(const ContactsCase& a, const ContactsCase& b, int trial) {
    for (size_t p = 0; p < a.x.size(); ++p) {
        EXPECT_TRUE(same(a.x[p], b.x[p])) << "trial " << trial << " particle " << p;
        EXPECT_TRUE(same(a.v[p], b.v[p])) << "trial " << trial << " particle " << p;
        EXPECT_TRUE(same(a.heldImpulse[p], b.heldImpulse[p]))
            << "trial " << trial << " particle " << p;
    }
    for (size_t k = 0; k < a.contacts.size(); ++k) {
        const ParticleContact &ca = a.contacts[k], &cb = b.contacts[k];
        EXPECT_TRUE(same(ca.lambdaNormal, cb.lambdaNormal))
            << "trial " << trial << " contact " << k;
        EXPECT_TRUE(same(ca.lambdaTangent, cb.lambdaTangent))
            << "trial " << trial << " contact " << k;
        EXPECT_TRUE(same(ca.frictionImpulse, cb.frictionImpulse))
            << "trial " << trial << " contact " << k;
    }
}

/// Both passes one by one, in order.
void solveOneByOne(ContactsCase& c) {
    const ContactParticles particles = c.particles();
    for (ParticleContact& contact : c.contacts) {
        if (contact.still)
            solveStillContactPosition(contact, particles, c.step);
        else
            solveMovingPosition(contact, particles);
    }
    for (const ParticleContact& contact : c.contacts) {
        if (contact.still)
            solveStillContactVelocity(contact, particles, c.step, false);
        else
            solveMovingVelocity(contact, particles);
    }
}

/// Both passes with groups of `group` in lanes; returns the groups solved so.
int solveInGroups(ContactsCase& c, int group) {
    const ContactParticles particles = c.particles();
    int groups = 0;
    forContactGroups(
        c.contacts, group,
        [&](size_t k, size_t count) {
            solveStillPositionGroups(&c.contacts[k], group, count, particles, c.step);
            groups += static_cast<int>((count + static_cast<size_t>(group) - 1) /
                                       static_cast<size_t>(group));
        },
        [&](size_t k) {
            ParticleContact& contact = c.contacts[k];
            if (contact.still)
                solveStillContactPosition(contact, particles, c.step);
            else
                solveMovingPosition(contact, particles);
        });
    forContactGroups(
        c.contacts, group,
        [&](size_t k, size_t count) {
            solveStillVelocityGroups(&c.contacts[k], group, count, particles, c.step);
        },
        [&](size_t k) {
            const ParticleContact& contact = c.contacts[k];
            if (contact.still)
                solveStillContactVelocity(contact, particles, c.step, false);
            else
                solveMovingVelocity(contact, particles);
        });
    return groups;
}

void expectLanesMatchOneByOne(int group) {
    Random random(0x5eed0000u + static_cast<uint64_t>(group));
    int groups = 0;
    for (int trial = 0; trial < 300; ++trial) {
        ContactsCase reference = randomCase(random);
        ContactsCase lanes = reference;
        // A second pass over the same contacts: λ and the friction impulses carried on.
        for (int pass = 0; pass < 2; ++pass) {
            solveOneByOne(reference);
            groups += solveInGroups(lanes, group);
        }
        expectSame(reference, lanes, trial);
        if (::testing::Test::HasFailure()) return;
    }
    EXPECT_GT(groups, 1000);
}

TEST(StillContacts, GroupsNeedStillContactsOnDistinctParticles) {
    std::vector<ParticleContact> contacts(8);
    for (uint32_t k = 0; k < 8; ++k)
        contacts[k] = {.particle = 7 - k, .still = true};
    EXPECT_TRUE(isStillGroup(contacts.data(), 8));
    EXPECT_TRUE(isStillGroup(contacts.data(), 0));
    contacts[5].particle = contacts[2].particle;
    EXPECT_FALSE(isStillGroup(contacts.data(), 8));
    EXPECT_TRUE(isStillGroup(contacts.data(), 4));
    contacts[5].particle = 100;
    contacts[7].still = false;
    EXPECT_FALSE(isStillGroup(contacts.data(), 8));
    EXPECT_TRUE(isStillGroup(contacts.data(), 7));
    // Rising particles (the usual order), one of them twice.
    for (uint32_t k = 0; k < 8; ++k)
        contacts[k] = {.particle = 2 * k, .still = true};
    EXPECT_TRUE(isStillGroup(contacts.data(), 8));
    contacts[4].particle = contacts[3].particle;
    EXPECT_FALSE(isStillGroup(contacts.data(), 8));
    EXPECT_TRUE(isStillGroup(contacts.data(), 4));
}

TEST(StillContacts, FourLanesGiveTheBitsOfOneByOne) {
    if (stillContactGroup(StillContactLanes::Avx2) != 4) GTEST_SKIP() << "no AVX2";
    expectLanesMatchOneByOne(4);
}

TEST(StillContacts, EightLanesGiveTheBitsOfOneByOne) {
    if (stillContactGroup(StillContactLanes::Widest) != 8) GTEST_SKIP() << "no AVX-512";
    expectLanesMatchOneByOne(8);
}

TEST(StillContacts, OneByOneTakesNoGroups) {
    EXPECT_EQ(stillContactGroup(StillContactLanes::OneByOne), 0);
    Random random(7);
    ContactsCase reference = randomCase(random);
    ContactsCase grouped = reference;
    solveOneByOne(reference);
    EXPECT_EQ(solveInGroups(grouped, 0), 0);
    expectSame(reference, grouped, 0);
}

}  // namespace
}  // namespace substep
