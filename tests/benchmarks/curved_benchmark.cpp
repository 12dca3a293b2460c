// Google Benchmark cases for the curved and complex shapes: closest points on a Hermite spline
// (the paper's most expensive part of the rolling ball sculpture) and the pair functions.
#include <benchmark/benchmark.h>

#include "../physics/collision/heightfield_reference.h"

#include "physics/collision/collide_curved.h"
#include "physics/collision/heightfield.h"
#include "physics/collision/heightfield_sphere.h"
#include "physics/collision/mesh_collider.h"
#include "physics/collision/spline_tube.h"

#include <cmath>
#include <random>
#include <vector>

namespace substep {
namespace {

/// A sculpture-like spring: a helix of radius 0.1 m, 20 turns, 16 control points per turn.
std::shared_ptr<const SplineTube> helix() {
    std::vector<Vec3> points;
    for (int i = 0; i <= 20 * 16; ++i) {
        const double a = 2.0 * M_PI * i / 16.0;
        points.emplace_back(0.1 * std::cos(a), 0.01 * a, 0.1 * std::sin(a));
    }
    return makeSplineTube(points, 0.002, false);
}

/// Marble centres resting on the wire (within a few millimetres of its surface).
std::vector<Vec3> marblesOn(const SplineTube& tube, double r, int count) {
    std::mt19937 rng(1);
    std::uniform_int_distribution<int> segment(0, static_cast<int>(tube.segments.size()) - 1);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<Vec3> centres;
    for (int i = 0; i < count; ++i) {
        const CubicSegment& s = tube.segments[segment(rng)];
        const double t = u(rng);
        const Vec3 side = anyPerpendicular(s.tangent(t).normalized());
        centres.push_back(s.point(t) + (tube.radius + r - 0.001 + 0.002 * u(rng)) * side);
    }
    return centres;
}

void BM_ClosestPointOnCubicSegment(benchmark::State& state) {
    const auto tube = helix();
    const auto queries = marblesOn(*tube, 0.01, 1024);
    std::size_t i = 0;
    for (auto _ : state) {
        const Vec3& q = queries[i++ & 1023];
        benchmark::DoNotOptimize(closestOnCubic(tube->segments[100], q));
    }
}
BENCHMARK(BM_ClosestPointOnCubicSegment);

/// Marble centres resting on one segment of the wire (as the narrowphase asks of the segments
/// next to a marble).
std::vector<Vec3> marblesOnSegment(const SplineTube& tube, int index, double r, int count) {
    std::mt19937 rng(2);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const CubicSegment& s = tube.segments[index];
    std::vector<Vec3> centres;
    for (int i = 0; i < count; ++i) {
        const double t = u(rng);
        const Vec3 tangent = s.tangent(t).normalized();
        const Vec3 side = Eigen::AngleAxisd(2.0 * M_PI * u(rng), tangent) * anyPerpendicular(tangent);
        centres.push_back(s.point(t) + (tube.radius + r - 0.001 + 0.002 * u(rng)) * side);
    }
    return centres;
}

// A marble on the segment: the scan, then Newton from the chord's projection.
void BM_ClosestPointNearSegmentScan(benchmark::State& state) {
    const auto tube = helix();
    const auto queries = marblesOnSegment(*tube, 100, 0.01, 1024);
    std::size_t i = 0;
    for (auto _ : state) benchmark::DoNotOptimize(closestOnCubic(tube->segments[100], queries[i++ & 1023]));
}
BENCHMARK(BM_ClosestPointNearSegmentScan);

void BM_ClosestPointNearSegmentFromChord(benchmark::State& state) {
    const auto tube = helix();
    const auto queries = marblesOnSegment(*tube, 100, 0.01, 1024);
    const CubicSegment& segment = tube->segments[100];
    std::size_t i = 0;
    for (auto _ : state) {
        const Vec3& q = queries[i++ & 1023];
        benchmark::DoNotOptimize(closestOnCubicFrom(segment, q, chordParameter(segment, q)));
    }
}
BENCHMARK(BM_ClosestPointNearSegmentFromChord);

// The same from the parameter found a substep earlier (the marble 3.3 mm back along the wire:
// 2 m/s over 1/600 s): what a per-pair warm start would gain over the chord's projection.
void BM_ClosestPointNearSegmentFromPrevious(benchmark::State& state) {
    const auto tube = helix();
    const auto queries = marblesOnSegment(*tube, 100, 0.01, 1024);
    const CubicSegment& segment = tube->segments[100];
    std::vector<double> previous;
    for (const Vec3& q : queries) {
        const Vec3 back = q - 0.0033 * segment.tangent(closestOnCubic(segment, q).t).normalized();
        previous.push_back(closestOnCubic(segment, back).t);
    }
    std::size_t i = 0;
    for (auto _ : state) {
        const std::size_t k = i++ & 1023;
        benchmark::DoNotOptimize(closestOnCubicFrom(segment, queries[k], previous[k]));
    }
}
BENCHMARK(BM_ClosestPointNearSegmentFromPrevious);

void BM_ClosestPointOnSpline(benchmark::State& state) {
    const auto tube = helix();
    const auto queries = marblesOn(*tube, 0.01, 1024);
    std::size_t i = 0;
    for (auto _ : state) {
        const Vec3& q = queries[i++ & 1023];
        benchmark::DoNotOptimize(tube->closestPoint(q, tube->radius + 0.011));
    }
}
BENCHMARK(BM_ClosestPointOnSpline);

void BM_SphereSpline(benchmark::State& state) {
    const Shape wire = splineShape(helix());
    const Shape marble = sphereShape(0.01);
    const auto queries = marblesOn(*wire.spline, 0.01, 1024);
    ContactManifold m;
    std::size_t i = 0;
    for (auto _ : state) {
        collideSphereSpline(marble, {queries[i++ & 1023], Quat::Identity()}, wire, {}, 0.001, m);
        benchmark::DoNotOptimize(m.count);
    }
}
BENCHMARK(BM_SphereSpline);

void BM_CapsuleSpline(benchmark::State& state) {
    const Shape wire = splineShape(helix());
    const Shape rod = capsuleShape(0.01, 0.05);
    const auto queries = marblesOn(*wire.spline, 0.01, 1024);
    ContactManifold m;
    std::size_t i = 0;
    for (auto _ : state) {
        collideCapsuleSpline(rod, {queries[i++ & 1023], Quat::Identity()}, wire, {}, 0.001, m);
        benchmark::DoNotOptimize(m.count);
    }
}
BENCHMARK(BM_CapsuleSpline);

/// A 64 x 64 grid of gentle bumps, as a mesh and as a heightfield.
std::vector<double> bumps(int n) {
    std::vector<double> h;
    for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i)
            h.push_back(0.1 * std::sin(0.4 * i) * std::cos(0.3 * j));
    }
    return h;
}

Shape bumpyMesh(int n) {
    const auto field = makeHeightfield(n, n, bumps(n), 16.0, 16.0);
    auto mesh = std::make_shared<TriangleMesh>();
    for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i)
            mesh->vertices.push_back(field->vertex(i, j));
    }
    for (int j = 0; j + 1 < n; ++j) {
        for (int i = 0; i + 1 < n; ++i) {
            const int a = j * n + i;
            mesh->triangles.push_back({a, a + n, a + n + 1});
            mesh->triangles.push_back({a, a + n + 1, a + 1});
        }
    }
    return triangleMeshShape(mesh);
}

void BM_SphereMesh(benchmark::State& state) {
    const Shape ground = bumpyMesh(64);
    const Shape ball = sphereShape(0.3);
    ContactManifold m;
    double x = -6.0;
    for (auto _ : state) {
        x = x > 6.0 ? -6.0 : x + 0.01;
        collideSphereMesh(ball, {Vec3(x, 0.3, 0.37 * x), Quat::Identity()}, ground, {}, 0.01, m);
        benchmark::DoNotOptimize(m.count);
    }
}
BENCHMARK(BM_SphereMesh);

void BM_BoxMesh(benchmark::State& state) {
    const Shape ground = bumpyMesh(64);
    const Shape box = boxShape({0.8, 0.4, 0.6});
    const Quat q(Eigen::AngleAxisd(0.3, Vec3(0.2, 1, 0.1).normalized()));
    ContactManifold m;
    double x = -6.0;
    for (auto _ : state) {
        x = x > 6.0 ? -6.0 : x + 0.01;
        collideBoxMesh(box, {Vec3(x, 0.25, 0.37 * x), q}, ground, {}, 0.01, m);
        benchmark::DoNotOptimize(m.count);
    }
}
BENCHMARK(BM_BoxMesh);

void BM_BoxHeightfield(benchmark::State& state) {
    const Shape ground = heightfieldShape(makeHeightfield(64, 64, bumps(64), 16.0, 16.0));
    const Shape box = boxShape({0.8, 0.4, 0.6});
    const Quat q(Eigen::AngleAxisd(0.3, Vec3(0.2, 1, 0.1).normalized()));
    ContactManifold m;
    double x = -6.0;
    for (auto _ : state) {
        x = x > 6.0 ? -6.0 : x + 0.01;
        collideBoxHeightfield(box, {Vec3(x, 0.25, 0.37 * x), q}, ground, {}, 0.01, m);
        benchmark::DoNotOptimize(m.count);
    }
}
BENCHMARK(BM_BoxHeightfield);

/// rc_car's case: 5 mm particles over 10 cm cells of bumps, their centres from 1.5 radii under
/// the surface to 2.5 above it (the candidates a substep tests). /0 the triangle-by-triangle
/// reference (the narrowphase before heightfield_sphere.cpp), /1 straight from the heights, /2
/// also with the cells' normals kept (as a soft body's grid keeps those under it).
void BM_ParticleHeightfield(benchmark::State& state) {
    const int n = 161;
    std::vector<double> heights;
    const auto surface = [](double x, double z) { return 0.015 * std::sin(3.5 * x) * std::sin(3.5 * x) * (0.6 + 0.4 * std::cos(4.5 * z)); };
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
            heights.push_back(surface(-8.0 + 0.1 * i, -8.0 + 0.1 * j));
    const auto field = makeHeightfield(n, n, heights, 16.0, 16.0);
    HeightfieldGrid grid(*field);
    if (state.range(0) == 2) grid.keepNormals({Vec3(-8, 0, -8), Vec3(8, 0, 8)}, n * n);
    const double r = 0.005, margin = 0.002;
    std::mt19937 rng(14);
    std::uniform_real_distribution<double> across(-6.0, 6.0), lift(-1.5 * r, 2.5 * r);
    std::vector<Vec3> centres;
    for (int k = 0; k < 1024; ++k) {
        const double x = across(rng), z = across(rng);
        centres.emplace_back(x, surface(x, z) + lift(rng), z);
    }
    const Pose pose;
    ContactManifold m;
    size_t k = 0;
    for (auto _ : state) {
        const Vec3& c = centres[k++ & 1023];
        if (state.range(0) == 0) reference::collideSphereHeightfield(*field, c, r, pose, margin, m);
        else collideSphereHeightfield(grid, c, r, pose, margin, m);
        benchmark::DoNotOptimize(m.count);
    }
}
BENCHMARK(BM_ParticleHeightfield)->Arg(0)->Arg(1)->Arg(2);

}  // namespace
}  // namespace substep
