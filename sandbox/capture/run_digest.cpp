#include "capture/run_digest.h"

#include <bit>
#include <cstdio>

namespace substep::capture {

void RunDigest::addValue(double value) {
    // Byte by byte from the least significant, so the digest does not depend on endianness.
    const std::uint64_t bits = std::bit_cast<std::uint64_t>(value);
    for (int byte = 0; byte < 8; ++byte) {
        hash_ ^= (bits >> (8 * byte)) & 0xffu;
        hash_ *= 1099511628211ull;  // FNV-1a 64 prime
    }
}

void RunDigest::add(const CaptureState& state) {
    if (firstFrame_ < 0) firstFrame_ = state.frame;
    lastFrame_ = state.frame;
    addValue(state.time);
    for (const BodyState& body : state.bodies) {
        for (const double value : body.position)
            addValue(value);
        for (const double value : body.orientation)
            addValue(value);
        for (const double value : body.velocity)
            addValue(value);
        for (const double value : body.angularVelocity)
            addValue(value);
    }
    for (const JointState& joint : state.joints) {
        addValue(joint.force);
        addValue(joint.torque);
        addValue(joint.error);
    }
    for (const SoftBodyState& soft : state.softBodies) {
        for (const double value : soft.centre)
            addValue(value);
        addValue(soft.volume);
    }
}

std::string RunDigest::line() const {
    char text[96];
    std::snprintf(text, sizeof text, "fnv1a64 %016llx frames %lld-%lld\n",
                  static_cast<unsigned long long>(hash_), firstFrame_, lastFrame_);
    return text;
}

}  // namespace substep::capture
