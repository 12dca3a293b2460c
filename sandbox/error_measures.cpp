#include "error_measures.h"

#include "ecs/components.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace substep {

ErrorReference errorReference(const SceneEntry* entry, const SceneInstance& scene) {
    ErrorReference reference;
    if (entry != nullptr) reference.chain = entry->chain;
    if (entry != nullptr && entry->energyScale > 0.0) {
        reference.energyScale = entry->energyScale;
        return reference;
    }
    // The weight lifted by 1 m: the energy a scene of this size trades in ordinary motion.
    double weight = 0.0;
    const double gravity = scene.world().settings().gravity.norm();
    for (const ecs::Entity entity : scene.bodyEntities)
        if (const auto* body = scene.registry.tryGet<ecs::RigidBody>(entity)) weight += body->simulatedMass * gravity;
    if (weight > 0.0 && std::isfinite(weight)) reference.energyScale = weight * 1.0;
    return reference;
}

ErrorRecorder::ErrorRecorder(const SceneInstance& scene, const ErrorReference& reference)
    : scene_(scene), reference_(reference) {
    // The scene's own joints, named or not (not those made later, such as the window's drag spring).
    for (const ecs::Entity entity : scene.jointEntities) {
        const ecs::Joint* joint = scene.registry.tryGet<ecs::Joint>(entity);
        if (joint != nullptr && !joint->id.isNull()) joints_.push_back(entity);
    }
    if (!reference_.chain.endBody.empty()) {
        const ecs::Entity end = scene.bodyNamed(reference_.chain.endBody);
        if (!end.isNull()) chainEnd_ = end;
        if (!chainEnd_) {
            throw std::invalid_argument("chain measure: no body named '" +
                                        std::string(reference_.chain.endBody) + "'");
        }
    }
}

void ErrorRecorder::sample() {
    const World& world = scene_.world();
    const double energy = world.energies().total();
    if (samples_ == 0) initialEnergy_ = energy;
    lastEnergy_ = energy;
    largestEnergyChange_ = std::max(largestEnergyChange_, std::abs(energy - initialEnergy_));

    double sum = 0.0;
    for (const ecs::Entity joint : joints_) {
        const ecs::Joint* component = scene_.registry.tryGet<ecs::Joint>(joint);
        const double error = component != nullptr ? component->readout.error : 0.0;
        sum += error;
        maxJointError_ = std::max(maxJointError_, error);
    }
    if (!joints_.empty()) jointErrorMeanSum_ += sum / static_cast<double>(joints_.size());
    penetration_ = std::max(penetration_, world.maxPenetration());
    ++samples_;

    // A non-finite sample poisons the measures for good: std::max ignores NaN, so say it here.
    if (!std::isfinite(energy) || !std::isfinite(sum)) {
        largestEnergyChange_ = maxJointError_ = INFINITY;
    }
}

ErrorMeasures ErrorRecorder::measures() const {
    ErrorMeasures result;
    if (samples_ == 0) return result;
    const double scale = reference_.energyScale;
    result.energyDrift = largestEnergyChange_ / scale;
    result.energyErrorFinal = std::abs(lastEnergy_ - initialEnergy_) / scale;
    result.maxJointError = maxJointError_;
    result.meanJointError = jointErrorMeanSum_ / static_cast<double>(samples_);
    result.penetration = penetration_;
    if (chainEnd_) {
        // The end point's world position, from the end body's own (user) frame.
        const ecs::Transform& end = scene_.registry.get<ecs::Transform>(*chainEnd_);
        const ChainMeasure& chain = reference_.chain;
        const Vec3 point =
            end.position + end.rotation * Vec3(chain.endPoint[0], chain.endPoint[1], chain.endPoint[2]);
        const Vec3 anchor(chain.anchor[0], chain.anchor[1], chain.anchor[2]);
        result.chainElongation = ((point - anchor).norm() - chain.restLength) / chain.restLength;
    }
    return result;
}

}  // namespace substep
