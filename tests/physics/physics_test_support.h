#pragma once
// Shared by the physics validation tests: closed-form mass properties, energies and momenta
// computed from the bodies' public state (not from the engine's own readouts), period
// measurement by zero crossings, and stepping helpers.

#include "physics/world.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace substep::test {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kDt = 1.0 / 60.0;

/// How many bodies of two worlds built alike differ in any bit of their pose or velocities.
inline int differingBodies(const World& a, const World& b) {
    int differing = 0;
    for (size_t i = 0; i < a.bodies().size(); ++i) {
        const Body& p = a.bodies()[i];
        const Body& q = b.bodies()[i];
        differing += std::memcmp(p.x.data(), q.x.data(), sizeof(double) * 3) != 0 ||
                     std::memcmp(p.q.coeffs().data(), q.q.coeffs().data(), sizeof(double) * 4) != 0 ||
                     std::memcmp(p.v.data(), q.v.data(), sizeof(double) * 3) != 0 ||
                     std::memcmp(p.omega.data(), q.omega.data(), sizeof(double) * 3) != 0;
    }
    return differing;
}

/// Box moments of inertia about its centre in its own frame: m (b² + c²)/12 and cyclic.
inline Vec3 boxMoments(const Vec3& size, double mass) {
    const Vec3 s = size.cwiseProduct(size);
    return Vec3(s.y() + s.z(), s.x() + s.z(), s.x() + s.y()) * (mass / 12.0);
}

/// World inertia tensor R diag(moments) Rᵀ of a body whose user frame is its principal frame
/// (a box or a sphere centred on its origin), from the closed-form moments.
inline Mat3 worldInertia(const Body& body, const Vec3& userMoments) {
    const Mat3 r = body.userOrientation().toRotationMatrix();
    return r * userMoments.asDiagonal() * r.transpose();
}

/// ½ m v² + ½ ωᵀ I ω with the closed-form inertia (the centre of mass is the user origin).
inline double kineticEnergy(const Body& body, double mass, const Vec3& userMoments) {
    return 0.5 * mass * body.v.squaredNorm() +
           0.5 * body.omega.dot(worldInertia(body, userMoments) * body.omega);
}

/// −m g·x of the centre of mass.
inline double potentialEnergy(const Body& body, double mass, const Vec3& gravity) {
    return -mass * gravity.dot(body.userPosition());
}

/// World angular momentum about the centre of mass, L = R I Rᵀ ω.
inline Vec3 angularMomentum(const Body& body, const Vec3& userMoments) {
    return worldInertia(body, userMoments) * body.omega;
}

/// A body-frame vector of the body's user frame, in world coordinates.
inline Vec3 userAxis(const Body& body, const Vec3& local) {
    return body.userOrientation() * local;
}

/// World point of a user-frame point.
inline Vec3 userPoint(const Body& body, const Vec3& local) {
    return body.userPosition() + body.userOrientation() * local;
}

/// World rotation vector (axis × angle) taking orientation `before` to `after`.
inline Vec3 turnBetween(const Quat& before, const Quat& after) {
    const Eigen::AngleAxisd turn((after * before.conjugate()).normalized());
    const double angle = turn.angle() > kPi ? turn.angle() - 2.0 * kPi : turn.angle();
    return turn.axis() * angle;
}

/// Angle between two unit vectors (rad), robust near 0 and π.
inline double angleBetween(const Vec3& a, const Vec3& b) {
    return std::atan2(a.cross(b).norm(), a.dot(b));
}

/// Steps `stepped` for `seconds` in frames of `dt`, calling `afterFrame(t)` after each frame.
/// `stepped` is a World (stepped directly) or a built scene (stepped through its physics system).
template <class Stepped, class AfterFrame>
void runFor(Stepped& stepped, double seconds, AfterFrame&& afterFrame, double dt = kDt) {
    const int frames = static_cast<int>(std::lround(seconds / dt));
    for (int f = 1; f <= frames; ++f) {
        if constexpr (requires { stepped.physics(); }) {
            stepped.physics().step(dt);
        } else {
            stepped.step(dt);
        }
        afterFrame(f * dt);
    }
}

template <class Stepped>
void runFor(Stepped& stepped, double seconds, double dt = kDt) {
    runFor(
        stepped, seconds, [](double) {}, dt);
}

/// A sampled signal s(t).
struct Signal {
    std::vector<double> t;
    std::vector<double> s;
    void add(double time, double value) {
        t.push_back(time);
        s.push_back(value);
    }
};

/// Times where the signal crosses zero (either direction), linearly interpolated.
inline std::vector<double> zeroCrossings(const Signal& signal) {
    std::vector<double> crossings;
    for (size_t i = 1; i < signal.s.size(); ++i) {
        const double a = signal.s[i - 1];
        const double b = signal.s[i];
        if ((a < 0.0 && b >= 0.0) || (a > 0.0 && b <= 0.0))
            crossings.push_back(signal.t[i - 1] + (signal.t[i] - signal.t[i - 1]) * a / (a - b));
    }
    return crossings;
}

/// Period of an oscillating signal from its zero crossings: two crossings per period, averaged
/// from the first to the last crossing. NaN with fewer than three crossings.
inline double measuredPeriod(const Signal& signal) {
    const std::vector<double> c = zeroCrossings(signal);
    if (c.size() < 3) return std::nan("");
    return 2.0 * (c.back() - c.front()) / static_cast<double>(c.size() - 1);
}

/// Prints a measured value next to the test output and records it in the XML report.
inline void report(const std::string& name, double value) {
    std::printf("[ measured ] %s = %.6g\n", name.c_str(), value);
    ::testing::Test::RecordProperty(name, std::to_string(value));
}

}  // namespace substep::test
