#include "capture/state_comparison.h"

#include "capture/json_input.h"

#include <cmath>

namespace substep::capture {

namespace {

class Comparer {
  public:
    Comparer(StateComparison& result) : result_(result) {}

    void value(const std::string& what, double golden, double fresh, const Tolerance& tolerance) {
        ++result_.compared;
        const double allowed = tolerance.abs + tolerance.rel * std::abs(golden);
        const double difference = std::abs(fresh - golden);
        // Written so that a NaN on either side counts as a difference.
        if (difference <= allowed) return;
        const StateDifference found{
            .what = what, .golden = golden, .fresh = fresh, .allowed = allowed};
        const double excess = std::isnan(difference) ? INFINITY : difference - allowed;
        if (result_.outOfTolerance == 0 || excess > worstExcess_) {
            result_.worst = found;
            worstExcess_ = excess;
        }
        ++result_.outOfTolerance;
        if (result_.differences.size() < kMaxListedDifferences)
            result_.differences.push_back(found);
    }

    template <std::size_t N>
    void values(const std::string& what, const std::array<double, N>& golden,
                const std::array<double, N>& fresh, const Tolerance& tolerance) {
        for (std::size_t i = 0; i < N; ++i)
            value(what + "[" + std::to_string(i) + "]", golden[i], fresh[i], tolerance);
    }

  private:
    StateComparison& result_;
    double worstExcess_ = 0.0;
};

const Tolerance& toleranceFor(const std::map<std::string, Tolerance>& named,
                              const std::string& name, const Tolerance& fallback) {
    if (name.empty()) return fallback;
    const auto found = named.find(name);
    return found == named.end() ? fallback : found->second;
}

/// "" when both lists name the same items in the same order, else what differs first.
template <typename T>
std::string structureDifference(const char* kind, const std::vector<T>& golden,
                                const std::vector<T>& fresh) {
    if (golden.size() != fresh.size()) {
        return std::string("the scene has ") + std::to_string(fresh.size()) + " " + kind +
               ", the golden " + std::to_string(golden.size());
    }
    for (std::size_t i = 0; i < golden.size(); ++i) {
        if (golden[i].name != fresh[i].name) {
            return std::string(kind) + "[" + std::to_string(i) + "] is named " +
                   jsonQuoted(fresh[i].name) + ", the golden's " + jsonQuoted(golden[i].name);
        }
    }
    return "";
}

std::string label(const char* kind, std::size_t index, const std::string& name) {
    std::string text(kind);
    text.append("[").append(std::to_string(index)).append("]");
    if (!name.empty()) text.append(" ").append(jsonQuoted(name));
    return text;
}

}  // namespace

StateComparison compareStates(const CaptureState& golden, const CaptureState& fresh,
                              const StateCheck& check) {
    StateComparison result;
    for (const std::string& difference :
         {structureDifference("bodies", golden.bodies, fresh.bodies),
          structureDifference("joints", golden.joints, fresh.joints),
          structureDifference("soft_bodies", golden.softBodies, fresh.softBodies)}) {
        if (result.structure.empty()) result.structure = difference;
    }
    if (!result.structure.empty()) return result;

    Comparer compare(result);
    compare.value("t", golden.time, fresh.time, check.tolerance);
    for (std::size_t i = 0; i < golden.bodies.size(); ++i) {
        const BodyState& a = golden.bodies[i];
        const BodyState& b = fresh.bodies[i];
        const Tolerance& tolerance = toleranceFor(check.bodies, a.name, check.tolerance);
        const std::string name = label("bodies", i, a.name);
        compare.values(name + ".position", a.position, b.position, tolerance);
        compare.values(name + ".orientation", a.orientation, b.orientation, tolerance);
        compare.values(name + ".velocity", a.velocity, b.velocity, tolerance);
        compare.values(name + ".angular_velocity", a.angularVelocity, b.angularVelocity, tolerance);
    }
    for (std::size_t i = 0; i < golden.joints.size(); ++i) {
        const JointState& a = golden.joints[i];
        const JointState& b = fresh.joints[i];
        const Tolerance& tolerance = toleranceFor(check.joints, a.name, check.tolerance);
        const std::string name = label("joints", i, a.name);
        compare.value(name + ".force", a.force, b.force, tolerance);
        compare.value(name + ".torque", a.torque, b.torque, tolerance);
        compare.value(name + ".error", a.error, b.error, tolerance);
    }
    for (std::size_t i = 0; i < golden.softBodies.size(); ++i) {
        const SoftBodyState& a = golden.softBodies[i];
        const SoftBodyState& b = fresh.softBodies[i];
        const Tolerance& tolerance = toleranceFor(check.bodies, a.name, check.tolerance);
        const std::string name = label("soft_bodies", i, a.name);
        compare.values(name + ".centre", a.centre, b.centre, tolerance);
        compare.value(name + ".volume", a.volume, b.volume, tolerance);
    }
    return result;
}

}  // namespace substep::capture
