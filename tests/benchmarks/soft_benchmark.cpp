// Benchmarks of engine/physics/soft: one tyre of 1100 hexahedral elements (44 around x 5 radial
// x 5 across, the paper's RC-car tyre) on a motorised rim rolling on the ground at 20 substeps
// (the Time column is per frame, dt = 1/60 s), and the cost of one shape-matching projection
// (the ns_per_element counter). Results go to docs/PERFORMANCE.md.

#include "physics/soft/soft_system.h"
#include "physics/world.h"

#include <benchmark/benchmark.h>

#include <cmath>

namespace {

using namespace substep;

constexpr double kDt = 1.0 / 60.0;

/// A carrier sliding along x, a rim turned by a hinge motor at 5 rad/s, its tyre attached by
/// the inner layer and pressed 3 mm onto the ground.
struct RollingTyre {
    World world;
    SoftBodyId tyre;

    RollingTyre() : world({.gravity = Vec3(0, -10, 0), .substeps = 20}) {
        const double ro = 0.3, ri = 0.2, width = 0.15, radius = 0.005;
        const double axle = ro + radius - 0.003;
        const Quat axisAlongZ(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitX()));
        world.createBody({.shape = planeShape(Vec3::UnitY(), 0.0), .type = BodyType::Static,
                          .staticFriction = 1.0, .dynamicFriction = 0.8});
        const BodyId carrier = world.createBody({.shape = boxShape(Vec3(0.1, 0.1, 0.1)), .mass = 5.0,
                                                 .position = Vec3(0, axle, 0), .collide = false});
        world.createJoint({.type = JointType::Prismatic, .body1 = carrier, .anchor0 = Vec3(0, axle, 0),
                           .axis0 = Vec3::UnitX(), .axis1 = Vec3::UnitX()});
        const BodyId rim = world.createBody({.shape = cylinderShape(ri, width), .density = 1000.0,
                                             .position = Vec3(0, axle, 0), .orientation = axisAlongZ,
                                             .collide = false});
        world.createJoint({.type = JointType::Hinge, .body0 = carrier, .body1 = rim, .axis0 = Vec3::UnitZ(),
                           .axis1 = Vec3::UnitY(), .targetVelocity = 5.0});
        SoftBodyDef def{.type = SoftBodyType::Tyre, .outerRadius = ro, .innerRadius = ri, .width = width,
                        .cells = {44, 5, 5}, .position = Vec3(0, axle, 0), .orientation = axisAlongZ,
                        .compliance = 1e-6, .damping = 5.0, .staticFriction = 1.0, .dynamicFriction = 0.8,
                        .particleRadius = radius};
        def.attachments.push_back({.body = rim, .particles = SoftAttachmentParticles::Inner});
        tyre = world.createSoftBody(def);
    }
};

void BM_TyreRolling(benchmark::State& state) {
    RollingTyre scene;
    for (int i = 0; i < 60; ++i) scene.world.step(kDt);  // warm-up second: gripping and rolling
    for (auto _ : state) scene.world.step(kDt);
    state.counters["elements"] = static_cast<double>(scene.world.softBodies()->elementCount());
    state.counters["speed_m_s"] = std::abs(scene.world.softBodyReadout(scene.tyre).velocity.x());
}
BENCHMARK(BM_TyreRolling)->Unit(benchmark::kMillisecond);

/// One Gauss-Seidel sweep over the rolling tyre's elements: rotation extraction warm-started
/// from the last sweep, goal positions, the XPBD update.
void BM_ElementProjection(benchmark::State& state) {
    RollingTyre scene;
    for (int i = 0; i < 60; ++i) scene.world.step(kDt);
    SoftSystem soft = *scene.world.softBodies();
    const double h = kDt / 20.0;
    for (auto _ : state) soft.solveElements(1.0 / (h * h));
    const double elements = static_cast<double>(soft.elementCount());
    state.counters["ns_per_element"] = benchmark::Counter(
        elements, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_ElementProjection)->Unit(benchmark::kMicrosecond);

/// The same sweep four lanes wide whatever the CPU (BM_ElementProjection runs eight where the
/// CPU has AVX-512): the two kernels side by side in one binary.
void BM_ElementProjectionFourLanes(benchmark::State& state) {
    RollingTyre scene;
    for (int i = 0; i < 60; ++i) scene.world.step(kDt);
    SoftSystem soft = *scene.world.softBodies();
    const double h = kDt / 20.0;
    for (auto _ : state) soft.solveElements(1.0 / (h * h), ElementLanes::Four);
    const double elements = static_cast<double>(soft.elementCount());
    state.counters["ns_per_element"] = benchmark::Counter(
        elements, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_ElementProjectionFourLanes)->Unit(benchmark::kMicrosecond);

}  // namespace
