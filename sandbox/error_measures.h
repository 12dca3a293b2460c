#pragma once
/// The error measures of a run (issue 6, "error against run time"): how far a simulated scene
/// strays from what the exact solution keeps, sampled frame by frame. `substep sweep` reports
/// them per split; any command that steps a scene can feed the same recorder.

#include "scene/scene.h"
#include "scenes/scene_registry.h"

#include <cstddef>
#include <optional>
#include <vector>

namespace substep {

/// What the measures are relative to.
struct ErrorReference {
    double energyScale = 1.0;  ///< J; energy errors are divided by it (must be > 0)
    ChainMeasure chain;        ///< chain.endBody empty: the scene has no chain measure
};

/// The reference for a scene: a built-in entry's energy scale and chain measure, else (entry
/// null, or its energyScale 0) the scene's weight times 1 m, Σ m|g| over its dynamic bodies;
/// 1 J when that is 0 too (no gravity, or nothing dynamic).
ErrorReference errorReference(const SceneEntry* entry, const SceneInstance& scene);

/// The measures of one run. Samples are the rows `substep run --csv` writes: the initial state,
/// then the state after each frame.
struct ErrorMeasures {
    double energyDrift = 0.0;       ///< max over samples of |E(t) − E(0)| / energyScale
    double energyErrorFinal = 0.0;  ///< |E(T) − E(0)| / energyScale at the last sample
    double maxJointError = 0.0;     ///< largest joint error over samples and joints (m)
    double meanJointError = 0.0;    ///< mean over samples of the mean over joints (m)
    /// (L − L0) / L0 at the last sample, L the anchor to end-point distance; none without a chain.
    std::optional<double> chainElongation;
    /// Deepest contact penetration over samples (m); 0 for a scene without contacts.
    double penetration = 0.0;
};

/// Accumulates ErrorMeasures over a run without storing the samples.
class ErrorRecorder {
  public:
    /// Throws std::invalid_argument when the reference names a chain end body the scene lacks.
    ErrorRecorder(const SceneInstance& scene, const ErrorReference& reference);

    /// Records the world's current state: once before the first step, then after every frame.
    void sample();

    /// The measures over every sample so far (all zero before the first).
    ErrorMeasures measures() const;
    std::size_t sampleCount() const { return samples_; }

  private:
    const SceneInstance& scene_;
    ErrorReference reference_;
    std::optional<ecs::Entity> chainEnd_;
    std::vector<ecs::Entity> joints_;  ///< the scene's joints, named or not

    std::size_t samples_ = 0;
    double initialEnergy_ = 0.0;
    double lastEnergy_ = 0.0;
    double largestEnergyChange_ = 0.0;
    double maxJointError_ = 0.0;
    double jointErrorMeanSum_ = 0.0;  ///< Σ over samples of the mean over joints
    double penetration_ = 0.0;
};

}  // namespace substep
