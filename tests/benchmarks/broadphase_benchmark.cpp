// Google Benchmark cases for the broadphase (engine/physics/collision/broadphase.cpp): one
// update per iteration, i.e. the time per frame, for both methods (argument 0 = AABB tree,
// 1 = sweep and prune, 2 = sweep and prune with boxes grown along the velocity only). The scenes
// follow PEERS.md's spheres1000 (1000 spheres r 0.1, a 3 x 3 m walled box on a ground plane) in two
// phases: the 10 x 10 x 10 grid falling, and the settled pile (4.4 layers of touching spheres,
// jiggling by a few mm). The bodies' motion is precomputed for 64 frames so that only the update is
// timed.

#include "physics/collision/broadphase.h"

#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

namespace {

using namespace substep;

constexpr double kDt = 1.0 / 60.0;
constexpr int kFrames = 64;

Body sphereBody(const Vec3& position) {
    return makeBody({.shape = sphereShape(0.1), .mass = 1.0, .position = position});
}

/// The anchor, the ground plane and four 3 m walls (inner faces at ±1.5 m).
std::vector<Body> walledBox() {
    std::vector<Body> bodies(1);
    bodies[0].alive = true;
    bodies.push_back(makeBody({.shape = planeShape(Vec3::UnitY(), 0.0), .type = BodyType::Static}));
    for (int side = 0; side < 4; ++side) {
        const double sign = side % 2 == 0 ? 1.0 : -1.0;
        const bool alongX = side < 2;
        const Vec3 size = alongX ? Vec3(0.2, 4.0, 3.4) : Vec3(3.4, 4.0, 0.2);
        const Vec3 position = alongX ? Vec3(sign * 1.6, 2.0, 0.0) : Vec3(0.0, 2.0, sign * 1.6);
        bodies.push_back(
            makeBody({.shape = boxShape(size), .type = BodyType::Static, .position = position}));
    }
    return bodies;
}

/// Frames of a scene: the bodies at each of kFrames frames (positions and velocities).
struct Recording {
    std::vector<Body> bodies;
    std::vector<std::vector<Vec3>> positions, velocities;  // [frame][sphere]
    size_t firstSphere = 0;

    void apply(int frame) {
        for (size_t i = 0; i < positions[frame].size(); ++i) {
            Body& body = bodies[firstSphere + i];
            body.x = positions[frame][i];
            body.v = velocities[frame][i];
        }
    }
};

/// The grid of 10 x 10 x 10 spheres 0.25 m apart falling at 3 to 8 m/s, with a little scatter
/// so that they do not move in lockstep.
Recording fallingGrid() {
    Recording r;
    r.bodies = walledBox();
    r.firstSphere = r.bodies.size();
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> scatter(-0.02, 0.02);
    std::vector<Vec3> base;
    for (int i = 0; i < 1000; ++i) {
        const Vec3 p(-1.125 + 0.25 * (i % 10), 3.0 + 0.25 * (i / 100),
                     -1.125 + 0.25 * (i / 10 % 10));
        base.push_back(p + Vec3(scatter(rng), scatter(rng), scatter(rng)));
        r.bodies.push_back(sphereBody(base.back()));
    }
    for (int f = 0; f < kFrames; ++f) {
        const double t = 0.3 + f * kDt * 0.5;  // half a frame per frame: the fall stays short
        std::vector<Vec3> x, v;
        for (const Vec3& p : base) {
            x.push_back(p - Vec3(0.0, 5.0 * t * t, 0.0));
            v.push_back(Vec3(0.05 * scatter(rng), -10.0 * t, 0.05 * scatter(rng)));
        }
        r.positions.push_back(x);
        r.velocities.push_back(v);
    }
    return r;
}

/// The settled pile: layers of 15 x 15 touching spheres on the ground, jiggling by ±4 mm.
Recording settledPile() {
    Recording r;
    r.bodies = walledBox();
    r.firstSphere = r.bodies.size();
    std::mt19937 rng(2);
    std::uniform_real_distribution<double> phase(0.0, 2.0 * M_PI);
    std::vector<Vec3> base, phases;
    for (int i = 0; i < 1000; ++i) {
        const Vec3 p(-1.4 + 0.2 * (i % 15), 0.1 + 0.2 * (i / 225), -1.4 + 0.2 * (i / 15 % 15));
        base.push_back(p);
        phases.push_back(Vec3(phase(rng), phase(rng), phase(rng)));
        r.bodies.push_back(sphereBody(p));
    }
    const double amplitude = 0.004;
    const double rate = 2.0 * M_PI / (kFrames * kDt);  // one period over the recording
    for (int f = 0; f < kFrames; ++f) {
        const double t = f * kDt;
        std::vector<Vec3> x, v;
        for (size_t i = 0; i < base.size(); ++i) {
            const Vec3 angle = (Vec3::Constant(rate * t) + phases[i]);
            x.push_back(base[i] + amplitude * angle.array().sin().matrix());
            v.push_back(amplitude * rate * angle.array().cos().matrix());
        }
        r.positions.push_back(x);
        r.velocities.push_back(v);
    }
    return r;
}

void runRecording(benchmark::State& state, Recording recording) {
    const auto method =
        state.range(0) == 0 ? BroadphaseMethod::AabbTree : BroadphaseMethod::SweepAndPrune;
    Broadphase broadphase({.method = method, .sweptGrowth = state.range(0) == 2});
    // A warm-up pass builds the trees and the sweep order.
    for (int f = 0; f < kFrames; ++f) {
        recording.apply(f);
        broadphase.update(recording.bodies, kDt);
    }
    int frame = 0;
    double pairs = 0.0;
    for (auto _ : state) {
        recording.apply(frame);
        broadphase.update(recording.bodies, kDt);
        pairs += static_cast<double>(broadphase.pairs().size());
        frame = (frame + 1) % kFrames;
    }
    state.counters["pairs"] = pairs / static_cast<double>(state.iterations());
    state.SetLabel(state.range(0) == 0   ? "tree"
                   : state.range(0) == 1 ? "sweep"
                                         : "sweep, swept growth");
}

void BM_BroadphaseSpheres1000Falling(benchmark::State& state) {
    runRecording(state, fallingGrid());
}
void BM_BroadphaseSpheres1000Pile(benchmark::State& state) {
    runRecording(state, settledPile());
}

/// The pile's bodies in place with no broadphase work but copying the frame in: the floor of
/// the figures above.
void BM_BroadphaseFrameCopyOnly(benchmark::State& state) {
    Recording recording = settledPile();
    int frame = 0;
    for (auto _ : state) {
        recording.apply(frame);
        benchmark::DoNotOptimize(recording.bodies.data());
        frame = (frame + 1) % kFrames;
    }
}

/// 2000 mixed bodies (spheres, boxes, capsules from 2 cm to 2 m, one in ten static) in a
/// 20 m cube, moving at up to 3 m/s and turning.
void BM_BroadphaseMixedSizes(benchmark::State& state) {
    Recording r;
    r.bodies.resize(1);
    r.bodies[0].alive = true;
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> position(-10.0, 10.0), unit(0.0, 1.0), speed(-3.0, 3.0);
    std::vector<size_t> movers;
    for (int i = 0; i < 2000; ++i) {
        const double s = 0.02 + 0.5 * std::pow(unit(rng), 4.0) * 4.0;
        const Shape shape = i % 3 == 0   ? sphereShape(0.5 * s)
                            : i % 3 == 1 ? boxShape(Vec3(s, 0.5 * s, s))
                                         : capsuleShape(0.25 * s, s);
        const bool isStatic = i % 10 == 0;
        r.bodies.push_back(makeBody({.shape = shape,
                                     .type = isStatic ? BodyType::Static : BodyType::Dynamic,
                                     .mass = 1.0,
                                     .position = Vec3(position(rng), position(rng), position(rng)),
                                     .angularVelocity = isStatic ? Vec3::Zero() : Vec3(1, 2, 0)}));
    }
    r.firstSphere = 1;
    std::vector<Vec3> v;
    for (size_t i = 1; i < r.bodies.size(); ++i) {
        v.push_back(r.bodies[i].isDynamic() ? Vec3(speed(rng), speed(rng), speed(rng))
                                            : Vec3::Zero());
    }
    for (int f = 0; f < kFrames; ++f) {
        std::vector<Vec3> x;
        for (size_t i = 1; i < r.bodies.size(); ++i) {
            // Out and back over the recording, so the loop closes.
            const double t = (f < kFrames / 2 ? f : kFrames - f) * kDt;
            x.push_back(r.bodies[i].x + v[i - 1] * t);
        }
        r.positions.push_back(x);
        r.velocities.push_back(v);
    }
    runRecording(state, r);
}

BENCHMARK(BM_BroadphaseSpheres1000Falling)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_BroadphaseSpheres1000Pile)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_BroadphaseMixedSizes)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_BroadphaseFrameCopyOnly)->Unit(benchmark::kMicrosecond);

}  // namespace
