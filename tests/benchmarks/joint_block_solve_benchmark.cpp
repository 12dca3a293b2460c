// Benchmarks of engine/physics/joint_block_solve.cpp: time per frame (dt = 1/60 s, 20 substeps)
// of worlds whose joints form clusters around light bodies, with the block solve on (argument 1)
// and off (0, joint-by-joint projection), so that the difference divided by the clusters and
// substeps is the cost of one cluster solve. Results go to docs/PERFORMANCE.md.

#include "physics/world.h"

#include <benchmark/benchmark.h>

namespace {

using namespace substep;

constexpr double kDt = 1.0 / 60.0;

WorldSettings settingsFor(const benchmark::State& state) {
    return WorldSettings{.gravity = Vec3(0.0, -10.0, 0.0), .substeps = 20, .blockSolve = state.range(0) != 0};
}

/// 10 pairs of mass_ratio's kind: a 1 g box on a hard distance joint to the world holding a 1 kg
/// box (one cluster of 6 rows each).
void BM_HangingPairs(benchmark::State& state) {
    World world(settingsFor(state));
    for (int i = 0; i < 10; ++i) {
        const Vec3 top(0.5 * i, 2.0, 0.0);
        const BodyId light = world.createBody({.shape = boxShape(Vec3::Constant(0.04)), .mass = 0.001,
                                               .position = top - Vec3(0.0, 0.02, 0.0)});
        const BodyId heavy = world.createBody({.shape = boxShape(Vec3::Constant(0.2)), .mass = 1.0,
                                               .position = top - Vec3(0.0, 0.14, 0.0)});
        world.createJoint({.type = JointType::Distance, .body1 = light, .anchor0 = top,
                           .anchor1 = Vec3(0.0, 0.02, 0.0)});
        world.createJoint({.type = JointType::Distance, .body0 = light, .body1 = heavy,
                           .anchor0 = Vec3(0.0, -0.02, 0.0), .anchor1 = Vec3(0.0, 0.1, 0.0)});
    }
    for (int i = 0; i < 60; ++i) world.step(kDt);
    for (auto _ : state) world.step(kDt);
    state.counters["clusters"] = static_cast<double>(world.jointClusterCount());
}
BENCHMARK(BM_HangingPairs)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

/// rc_car's steering linkage alone, weightless: a 0.1 g servo arm on a driven hinge to a 1.2 kg
/// chassis, two 1 g rods on ball joints to 20 g knuckles on hinges to the chassis (one cluster
/// of 7 + 4 x 3 + 2 x 7 = 33 rows, the knuckles' hinges closing the loops).
void BM_SteeringLinkage(benchmark::State& state) {
    WorldSettings settings = settingsFor(state);
    settings.gravity = Vec3::Zero();
    World world(settings);
    const BodyId chassis = world.createBody({.shape = boxShape(Vec3(0.4, 0.05, 0.3)), .mass = 1.2});
    const BodyId arm = world.createBody({.shape = boxShape(Vec3(0.06, 0.004, 0.008)), .mass = 1e-4,
                                         .position = Vec3(0.15, 0.0, 0.0)});
    world.createJoint({.type = JointType::Hinge, .body0 = chassis, .body1 = arm, .anchor0 = Vec3(0.15, 0.0, 0.0),
                       .targetAngle = 0.0, .driveCompliance = 1e-3});
    for (const double z : {-1.0, 1.0}) {
        const BodyId knuckle = world.createBody({.shape = boxShape(Vec3(0.04, 0.015, 0.015)), .mass = 0.02,
                                                 .position = Vec3(0.15, 0.0, 0.13 * z)});
        world.createJoint({.type = JointType::Hinge, .body0 = chassis, .body1 = knuckle,
                           .anchor0 = Vec3(0.15, 0.0, 0.13 * z), .limits = Range{-0.6, 0.6}});
        const BodyId rod = world.createBody({.shape = capsuleShape(0.003, 0.13), .mass = 1e-3,
                                             .position = Vec3(0.12, 0.0, 0.065 * z),
                                             .orientation = Quat(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitX()))});
        world.createJoint({.type = JointType::Spherical, .body0 = knuckle, .body1 = rod,
                           .anchor0 = Vec3(-0.03, 0.0, 0.0), .anchor1 = Vec3(0.0, 0.065 * z, 0.0)});
        world.createJoint({.type = JointType::Spherical, .body0 = arm, .body1 = rod,
                           .anchor0 = Vec3(-0.03, 0.0, 0.0), .anchor1 = Vec3(0.0, -0.065 * z, 0.0)});
    }
    for (int i = 0; i < 60; ++i) world.step(kDt);
    for (auto _ : state) world.step(kDt);
    state.counters["clusters"] = static_cast<double>(world.jointClusterCount());
}
BENCHMARK(BM_SteeringLinkage)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

}  // namespace
