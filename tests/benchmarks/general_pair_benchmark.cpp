// Google Benchmark cases for the general convex pair (engine/physics/collision/convex_manifold.cpp,
// gjk_epa.cpp, collide_convex_triangles.cpp, collide_convex_spline.cpp): one collide() call per
// iteration, dispatch included, on resting and touching configurations. Where a special routine
// exists, the same pose runs through the table (Special) and through the general pair (General).
//   taskset -c 0 build/bin/substep_benchmarks --benchmark_filter='Special|General'

#include "physics/collision/collide_convex.h"
#include "physics/collision/convex_manifold.h"
#include "physics/collision/convex_mesh_shape.h"
#include "physics/collision/heightfield.h"
#include "physics/collision/mesh_collider.h"
#include "physics/collision/narrowphase.h"
#include "physics/collision/spline_tube.h"

#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

namespace {

using namespace substep;

Quat turn(double angle, const Vec3& axis) {
    return Quat(Eigen::AngleAxisd(angle, axis.normalized()));
}

Shape boxHull(const Vec3& size) {
    auto mesh = std::make_shared<TriangleMesh>();
    for (int i = 0; i < 8; ++i) {
        mesh->vertices.emplace_back(i & 1 ? 0.5 * size.x() : -0.5 * size.x(),
                                    i & 2 ? 0.5 * size.y() : -0.5 * size.y(),
                                    i & 4 ? 0.5 * size.z() : -0.5 * size.z());
    }
    return convexMeshShape(mesh);
}

/// A rounded hull of 200 points on an ellipsoid (a pebble, a bunny-sized hull).
Shape pebble() {
    auto mesh = std::make_shared<TriangleMesh>();
    const double golden = M_PI * (3.0 - std::sqrt(5.0));
    for (int i = 0; i < 200; ++i) {
        const double y = 1.0 - 2.0 * (i + 0.5) / 200;
        const double r = std::sqrt(1.0 - y * y);
        mesh->vertices.emplace_back(0.15 * r * std::cos(golden * i), 0.1 * y,
                                    0.12 * r * std::sin(golden * i));
    }
    return convexMeshShape(mesh);
}

Shape groundMesh() {
    auto mesh = std::make_shared<TriangleMesh>();
    // A 10 x 10 grid of 1 m cells at y = 0.
    for (int j = 0; j <= 10; ++j)
        for (int i = 0; i <= 10; ++i)
            mesh->vertices.emplace_back(i - 5.0, 0.0, j - 5.0);
    for (int j = 0; j < 10; ++j) {
        for (int i = 0; i < 10; ++i) {
            const int v = j * 11 + i;
            mesh->triangles.push_back({v, v + 11, v + 12});
            mesh->triangles.push_back({v, v + 12, v + 1});
        }
    }
    return triangleMeshShape(mesh);
}

Shape bumpyField() {
    std::vector<double> heights;
    for (int j = 0; j < 33; ++j)
        for (int i = 0; i < 33; ++i)
            heights.push_back(0.02 * std::sin(0.7 * i) * std::cos(0.5 * j));
    return heightfieldShape(makeHeightfield(33, 33, heights, 8.0, 8.0));
}

Shape rails() {
    std::vector<Vec3> points;
    for (int i = 0; i <= 8; ++i)
        points.emplace_back(i - 4.0, -0.02, 0.0);
    return splineShape(makeSplineTube(points, 0.02, false));
}

template <class Collide>
void runPair(benchmark::State& state, Collide&& collideFn, const Shape& a, const Pose& pa,
             const Shape& b, const Pose& pb) {
    ContactManifold manifold;
    for (auto _ : state) {
        manifold.clear();
        collideFn(a, pa, b, pb, 0.01, manifold);
        benchmark::DoNotOptimize(manifold);
        benchmark::ClobberMemory();
    }
    state.counters["points"] = manifold.count;
}

void Special(benchmark::State& state, const Shape& a, const Pose& pa, const Shape& b, const Pose& pb) {
    runPair(state, collide, a, pa, b, pb);
}
void General(benchmark::State& state, const Shape& a, const Pose& pa, const Shape& b, const Pose& pb) {
    runPair(state, collideGeneralConvex, a, pa, b, pb);
}

/// The hull's own separating-axis routines, called directly (the table sends capsule–hull and
/// large hull pairs to the general pair).
void SeparatingAxes(benchmark::State& state, CollideFunction function, const Shape& a,
                    const Pose& pa, const Shape& b, const Pose& pb) {
    runPair(state, function, a, pa, b, pb);
}

const Pose kOrigin{};
const Pose kResting{Vec3(0.05, 0.599, -0.03), turn(0.02, Vec3(0.1, 1, 0.2))};  // on a unit box
const Pose kTilted{Vec3(0.05, 0.62, -0.03), turn(0.5, Vec3(1, 0, 0.3))};
const Pose kOnGround{Vec3(0.3, 0.099, 0.2), turn(0.02, Vec3(0.1, 1, 0.2))};

const Shape kUnitBox = boxShape(Vec3(1, 1, 1));
const Shape kUnitHull = boxHull(Vec3(1, 1, 1));
const Shape kSmallBox = boxShape(Vec3(0.3, 0.2, 0.3));
const Shape kSmallHull = boxHull(Vec3(0.3, 0.2, 0.3));
const Shape kCan = cylinderShape(0.15, 0.2);
const Shape kCapsule = capsuleShape(0.1, 0.3);
const Shape kSphere = sphereShape(0.1);

// Both routes on the same pose.
#define BOTH(name, ...)                         \
    BENCHMARK_CAPTURE(Special, name, __VA_ARGS__); \
    BENCHMARK_CAPTURE(General, name, __VA_ARGS__)

BOTH(box_box_resting, kSmallBox, kResting, kUnitBox, kOrigin);
BOTH(box_box_tilted, kSmallBox, kTilted, kUnitBox, kOrigin);
BOTH(hull_hull_resting, kSmallHull, kResting, kUnitHull, kOrigin);
BOTH(box_hull_resting, kSmallBox, kResting, kUnitHull, kOrigin);
BOTH(sphere_hull, kSphere, Pose{Vec3(0.1, 0.595, 0), Quat::Identity()}, kUnitHull, kOrigin);
BOTH(capsule_hull_lying, kCapsule, Pose{Vec3(0.1, 0.595, 0), turn(M_PI / 2, Vec3::UnitZ())}, kUnitHull, kOrigin);
BOTH(capsule_hull_tilted, kCapsule, Pose{Vec3(0.1, 0.7, 0), turn(0.6, Vec3::UnitZ())}, kUnitHull, kOrigin);
BOTH(cylinder_box_flat, kCan, kResting, kUnitBox, kOrigin);
BOTH(cylinder_box_tilted, kCan, kTilted, kUnitBox, kOrigin);
BOTH(cylinder_sphere, kCan, Pose{Vec3(0.05, 0.0, 0.0), Quat::Identity()}, sphereShape(0.1), Pose{Vec3(0.05, 0.195, 0), Quat::Identity()});
BOTH(capsule_capsule, kCapsule, Pose{Vec3(0, 0.195, 0), turn(1.0, Vec3::UnitZ())}, kCapsule, kOrigin);
BOTH(pebble_pebble, pebble(), Pose{Vec3(0.02, 0.195, 0), turn(0.3, Vec3(1, 1, 0))}, pebble(), kOrigin);
BENCHMARK_CAPTURE(SeparatingAxes, capsule_hull_lying, collideCapsuleConvex, kCapsule, Pose{Vec3(0.1, 0.595, 0), turn(M_PI / 2, Vec3::UnitZ())}, kUnitHull, kOrigin);
BENCHMARK_CAPTURE(SeparatingAxes, capsule_hull_tilted, collideCapsuleConvex, kCapsule, Pose{Vec3(0.1, 0.7, 0), turn(0.6, Vec3::UnitZ())}, kUnitHull, kOrigin);
BENCHMARK_CAPTURE(SeparatingAxes, pebble_pebble, collideConvexConvex, pebble(), Pose{Vec3(0.02, 0.195, 0), turn(0.3, Vec3(1, 1, 0))}, pebble(), kOrigin);

// Pairs only the general routine serves.
BENCHMARK_CAPTURE(Special, cylinder_cylinder_flat, kCan, Pose{Vec3(0.05, 0.199, 0), Quat::Identity()}, kCan, kOrigin);
BENCHMARK_CAPTURE(Special, cylinder_capsule, kCan, kOrigin, kCapsule, Pose{Vec3(0.0, 0.195, 0), turn(M_PI / 2, Vec3::UnitZ())});
BENCHMARK_CAPTURE(Special, cylinder_hull_flat, kCan, kResting, kUnitHull, kOrigin);
BENCHMARK_CAPTURE(Special, cylinder_pebble, kCan, Pose{Vec3(0, 0.195, 0), turn(0.2, Vec3::UnitX())}, pebble(), kOrigin);
BENCHMARK_CAPTURE(Special, cylinder_mesh_flat, kCan, kOnGround, groundMesh(), kOrigin);
BENCHMARK_CAPTURE(Special, hull_mesh_flat, kSmallHull, kOnGround, groundMesh(), kOrigin);
BENCHMARK_CAPTURE(Special, box_mesh_flat, kSmallBox, kOnGround, groundMesh(), kOrigin);
BENCHMARK_CAPTURE(Special, cylinder_heightfield, kCan, kOnGround, bumpyField(), kOrigin);
BENCHMARK_CAPTURE(Special, hull_heightfield, kSmallHull, kOnGround, bumpyField(), kOrigin);
BENCHMARK_CAPTURE(Special, box_heightfield, kSmallBox, kOnGround, bumpyField(), kOrigin);
BENCHMARK_CAPTURE(Special, box_spline_across, kSmallBox, Pose{Vec3(0.3, 0.099, 0), Quat::Identity()}, rails(), kOrigin);
BENCHMARK_CAPTURE(Special, box_spline_along, boxShape(Vec3(0.6, 0.2, 0.1)), Pose{Vec3(0.3, 0.099, 0), Quat::Identity()}, rails(), kOrigin);
BENCHMARK_CAPTURE(Special, hull_spline, kSmallHull, Pose{Vec3(0.3, 0.099, 0), Quat::Identity()}, rails(), kOrigin);
BENCHMARK_CAPTURE(Special, cylinder_spline_side, kCan, Pose{Vec3(0.3, 0.149, 0), turn(M_PI / 2, Vec3::UnitX())}, rails(), kOrigin);
BENCHMARK_CAPTURE(Special, sphere_spline, kSphere, Pose{Vec3(0.3, 0.099, 0), Quat::Identity()}, rails(), kOrigin);

}  // namespace
