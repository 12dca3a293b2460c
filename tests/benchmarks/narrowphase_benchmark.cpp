// Google Benchmark cases for the narrowphase (engine/physics/collision/narrowphase.cpp): the
// time of one collide() call, dispatch included, on the configurations the solver meets most
// (it re-runs the narrowphase every substep for every close pair).

#include "physics/collision/narrowphase.h"

#include <benchmark/benchmark.h>

#include <cmath>

namespace {

using namespace substep;

Quat turn(double angle, const Vec3& axis) {
    return Quat(Eigen::AngleAxisd(angle, axis.normalized()));
}

/// Runs collide() on one pair; `points` counts the contacts of the last call.
void runPair(benchmark::State& state, const Shape& a, const Pose& pa, const Shape& b,
             const Pose& pb, double margin) {
    ContactManifold manifold;
    for (auto _ : state) {
        collide(a, pa, b, pb, margin, manifold);
        benchmark::DoNotOptimize(manifold);
        benchmark::ClobberMemory();
    }
    state.counters["points"] = manifold.count;
}

/// A box resting flat on a box (slightly turned and offset, as in a settling stack): 4 points.
void NarrowBoxBoxResting(benchmark::State& state) {
    const Shape box = boxShape(Vec3(1, 1, 1));
    runPair(state, box, {Vec3(0.05, 0.99, -0.03), turn(0.02, Vec3(0.1, 1, 0.2))}, box,
            {Vec3::Zero(), Quat::Identity()}, 0.01);
}
BENCHMARK(NarrowBoxBoxResting);

/// Two boxes touching edge to edge: one point.
void NarrowBoxBoxEdge(benchmark::State& state) {
    const Shape box = boxShape(Vec3(1, 1, 1));
    runPair(state, box, {Vec3::Zero(), turn(M_PI / 4, Vec3::UnitZ())}, box,
            {Vec3(0, std::sqrt(2.0) - 0.01, 0), turn(M_PI / 4, Vec3::UnitX())}, 0.01);
}
BENCHMARK(NarrowBoxBoxEdge);

/// Boxes apart by more than the margin (the separating-axis early out).
void NarrowBoxBoxSeparated(benchmark::State& state) {
    const Shape box = boxShape(Vec3(1, 1, 1));
    runPair(state, box, {Vec3(0.3, 1.2, 0.1), turn(0.4, Vec3(1, 2, 3))}, box,
            {Vec3::Zero(), Quat::Identity()}, 0.01);
}
BENCHMARK(NarrowBoxBoxSeparated);

/// A box resting on the ground plane: 4 corners.
void NarrowBoxPlane(benchmark::State& state) {
    runPair(state, boxShape(Vec3(1, 1, 1)), {Vec3(0, 0.499, 0), turn(0.01, Vec3(1, 0, 1))},
            planeShape(Vec3::UnitY(), 0.0), {}, 0.01);
}
BENCHMARK(NarrowBoxPlane);

/// Two overlapping spheres.
void NarrowSphereSphere(benchmark::State& state) {
    const Shape ball = sphereShape(0.5);
    runPair(state, ball, {Vec3(0.1, 0.95, 0), Quat::Identity()}, ball,
            {Vec3::Zero(), Quat::Identity()}, 0.01);
}
BENCHMARK(NarrowSphereSphere);

/// Two crossing capsules: one point.
void NarrowCapsuleCapsule(benchmark::State& state) {
    const Shape capsule = capsuleShape(0.25, 1.0);
    runPair(state, capsule, {Vec3(0, 0.49, 0), turn(M_PI / 2, Vec3::UnitZ())}, capsule,
            {Vec3::Zero(), turn(M_PI / 2, Vec3::UnitX())}, 0.01);
}
BENCHMARK(NarrowCapsuleCapsule);

/// Two parallel capsules side by side: two points.
void NarrowCapsuleCapsuleParallel(benchmark::State& state) {
    const Shape capsule = capsuleShape(0.25, 1.0);
    runPair(state, capsule, {Vec3(0, 0.48, 0.1), turn(M_PI / 2, Vec3::UnitZ())}, capsule,
            {Vec3::Zero(), turn(M_PI / 2, Vec3::UnitZ())}, 0.01);
}
BENCHMARK(NarrowCapsuleCapsuleParallel);

/// A capsule lying on a box: two points (the deepest point found by golden-section search).
void NarrowCapsuleBox(benchmark::State& state) {
    runPair(state, capsuleShape(0.25, 1.0), {Vec3(0.1, 0.74, 0), turn(M_PI / 2, Vec3::UnitZ())},
            boxShape(Vec3(2, 1, 2)), {Vec3::Zero(), Quat::Identity()}, 0.01);
}
BENCHMARK(NarrowCapsuleBox);

/// A sphere resting on a box.
void NarrowSphereBox(benchmark::State& state) {
    runPair(state, sphereShape(0.5), {Vec3(0.1, 0.99, 0), Quat::Identity()},
            boxShape(Vec3(2, 1, 2)), {Vec3::Zero(), turn(0.1, Vec3::UnitY())}, 0.01);
}
BENCHMARK(NarrowSphereBox);

}  // namespace
