#pragma once
/// The per-frame record of DESIGN.md's `--csv` contract: which columns there are and how one
/// row of them is sampled from a world. Shared by `run` and the commands that will record the
/// same state (`capture`).

#include "scene/scene.h"

#include <cstddef>
#include <string>
#include <vector>

namespace substep {

/// Positions in a sampled row (sampleState's `values`, which start at `t`).
inline constexpr std::size_t kStateTime = 0;
inline constexpr std::size_t kStateEnergy = 4;
inline constexpr std::size_t kStateMaxError = 5;

/// Column names in contract order: `frame,t,kinetic,potential,elastic,energy,max_error`, then
/// 13 per named body (user-frame pose, velocities), then 3 per named joint, then 10 per named
/// soft body (centre of mass, velocity, extent, volume).
std::vector<std::string> stateColumnNames(const SceneInstance& scene);

/// Fills `values` with every column after `frame` for the world's current state at time t.
/// `values` is resized once and reused, so sampling every frame allocates nothing.
void sampleState(const SceneInstance& scene, double t, std::vector<double>& values);

}  // namespace substep
