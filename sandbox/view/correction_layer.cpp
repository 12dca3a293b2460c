#include "view/correction_layer.h"

#include "ecs/components.h"
#include "physics/collision/shape_bounds.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <unordered_map>

namespace substep::view {

namespace {

const char* typeName(JointType type) {
    switch (type) {
        case JointType::Distance:
            return "distance joint";
        case JointType::Fixed:
            return "fixed joint";
        case JointType::Hinge:
            return "hinge";
        case JointType::Spherical:
            return "ball joint";
        case JointType::Prismatic:
            return "prismatic joint";
    }
    return "joint";
}

/// Names of the world's bodies and joints by storage index, from the components.
struct Names {
    std::unordered_map<uint32_t, std::string> bodies;
    std::unordered_map<uint32_t, std::string> joints;

    explicit Names(ecs::Registry& registry) {
        registry.view<ecs::RigidBody>().each([&](ecs::Entity entity, const ecs::RigidBody& body) {
            if (body.id.isNull()) return;
            const ecs::Name* name = registry.tryGet<ecs::Name>(entity);
            bodies[body.id.index] =
                "'" + (name ? name->value : "body " + std::to_string(entity.index)) + "'";
        });
        registry.view<ecs::Joint>().each([&](ecs::Entity entity, const ecs::Joint& joint) {
            if (joint.id.isNull()) return;
            const ecs::Name* name = registry.tryGet<ecs::Name>(entity);
            joints[joint.id.index] =
                std::string(typeName(joint.def.type)) + " '" +
                (name ? name->value : "joint " + std::to_string(entity.index)) + "'";
        });
    }
    std::string body(uint32_t index) const {
        if (index == 0) return "the world";
        const auto found = bodies.find(index);
        return found != bodies.end() ? found->second : "body #" + std::to_string(index);
    }
    std::string joint(uint32_t index) const {
        const auto found = joints.find(index);
        return found != joints.end() ? found->second : "joint #" + std::to_string(index);
    }
};

}  // namespace

std::string formatLength(double metres) {
    const double size = std::abs(metres);
    char text[48];
    if (size >= 1.0) {
        std::snprintf(text, sizeof text, "%.3g m", metres);
    } else if (size >= 1e-4) {
        std::snprintf(text, sizeof text, "%.3g mm", metres * 1e3);
    } else if (size >= 1e-7) {
        std::snprintf(text, sizeof text, "%.3g um", metres * 1e6);
    } else {
        std::snprintf(text, sizeof text, "%.3g nm", metres * 1e9);
    }
    return text;
}

std::string CorrectionEntry::describe() const {
    std::string text = constraint + " moved " + body + " " + formatLength(displacement.norm());
    const double angle = rotation.norm();
    if (angle > 0.0) {
        char turned[48];
        std::snprintf(turned, sizeof turned, ", turned it %.3g deg", angle * 180.0 / M_PI);
        text += turned;
    }
    return text;
}

std::vector<CorrectionEntry> listCorrections(SceneInstance& scene) {
    std::vector<CorrectionEntry> entries;
    const World& world = scene.world();
    const SubstepCorrections* corrections = world.corrections();
    if (corrections == nullptr || corrections->substep() == 0) return entries;
    const Names names(scene.registry);
    const std::span<const Body> bodies = world.bodies();
    for (const ConstraintCorrection& c : corrections->constraints()) {
        const std::string constraint =
            c.kind == ConstraintKind::Joint
                ? names.joint(c.index)
                : "contact " + names.body(c.body0) + " / " + names.body(c.body1);
        const auto add = [&](uint32_t index, const Vec3& displacement, const Vec3& rotation) {
            if (index >= bodies.size() || bodies[index].invMass == 0.0) return;
            const double reach = shapeReach(bodies[index].shape);
            const double size =
                displacement.norm() + rotation.norm() * (std::isfinite(reach) ? reach : 0.0);
            if (!(size > 0.0)) return;
            entries.push_back({.constraint = constraint,
                               .body = names.body(index),
                               .kind = c.kind,
                               .bodyIndex = index,
                               .displacement = displacement,
                               .rotation = rotation,
                               .size = size});
        };
        add(c.body0, c.displacement0, c.rotation0);
        if (c.body1 != c.body0) add(c.body1, c.displacement1, c.rotation1);
    }
    // Largest first; ties keep the solve order, so the list is the same every time.
    std::stable_sort(
        entries.begin(), entries.end(),
        [](const CorrectionEntry& a, const CorrectionEntry& b) { return a.size > b.size; });
    return entries;
}

void drawCorrections(const std::vector<CorrectionEntry>& entries, const World& world,
                     std::vector<render::DebugLine>& lines) {
    if (entries.empty()) return;
    const std::span<const Body> bodies = world.bodies();
    // One scale for every arrow, so their lengths compare: the largest motion drawn about twice
    // its body's size (a correction is micrometres; drawn true to scale nothing would show).
    const CorrectionEntry& largest = entries.front();
    const double reach =
        largest.bodyIndex < bodies.size() ? shapeReach(bodies[largest.bodyIndex].shape) : 0.0;
    const double length = std::isfinite(reach) && reach > 0.0 ? 2.0 * reach : 0.5;
    const double scale = length / largest.size;
    // Colours no debug layer uses (torques are orange, forces magenta, limits cyan, axes red,
    // green and blue).
    const render::Colour move(0.6f, 1.0f, 0.0f);
    const render::Colour turn(1.0f, 1.0f, 1.0f);
    const auto arrow = [&](const Vec3& from, const Vec3& vector, const render::Colour& colour) {
        const double size = vector.norm();
        if (!(size > 0.0) || !from.allFinite()) return;
        const Vec3 to = from + vector;
        lines.push_back({from.cast<float>(), to.cast<float>(), colour});
        // A head of two strokes, a fifth of the arrow, in a plane holding it.
        const Vec3 along = vector / size;
        const Vec3 side =
            (std::abs(along.y()) < 0.9 ? along.cross(Vec3::UnitY()) : along.cross(Vec3::UnitX()))
                .normalized();
        for (const double sign : {-1.0, 1.0})
            lines.push_back({to.cast<float>(),
                             (to - 0.2 * size * along + sign * 0.1 * size * side).cast<float>(),
                             colour});
    };
    for (const CorrectionEntry& entry : entries) {
        if (entry.bodyIndex >= bodies.size()) continue;
        const Vec3& centre = bodies[entry.bodyIndex].x;
        const double bodyReach = shapeReach(bodies[entry.bodyIndex].shape);
        arrow(centre, scale * entry.displacement, move);
        if (std::isfinite(bodyReach)) arrow(centre, scale * bodyReach * entry.rotation, turn);
    }
}

}  // namespace substep::view
