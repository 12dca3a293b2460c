#include "view/correction_layer.h"

#include "ecs/components.h"
#include "ecs/soft_body_component.h"
#include "physics/soft/soft_system.h"
#include "physics/collision/shape_bounds.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <unordered_map>

namespace substep::view {

namespace {

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
                std::string(jointTypeName(joint.def.type)) + " joint '" +
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
    /// What a recorded constraint is called in the panel.
    std::string constraint(ConstraintKind kind, uint32_t index, uint32_t body0, uint32_t body1) const {
        switch (kind) {
            case ConstraintKind::Joint:
                return joint(index);
            case ConstraintKind::Contact:
                return "contact " + body(body0) + " / " + body(body1);
            case ConstraintKind::SoftAttachments:
                return "soft attachments";
            case ConstraintKind::SoftContacts:
                return "soft contacts";
        }
        return "constraint";
    }
};

/// The colours of the arrows: lime moves, white turns (correction_layer.h), pink velocity
/// changes; colours no debug layer uses (torques are orange, forces magenta, limits cyan, axes
/// red, green and blue).
const render::Colour kMoveColour(0.6f, 1.0f, 0.0f);
const render::Colour kTurnColour(1.0f, 1.0f, 1.0f);
const render::Colour kVelocityColour(1.0f, 0.45f, 0.75f);

/// An arrow from `from` along `vector` with a head of two strokes, a fifth of its length.
void arrow(const Vec3& from, const Vec3& vector, const render::Colour& colour,
           std::vector<render::DebugLine>& lines) {
    const double size = vector.norm();
    if (!(size > 0.0) || !from.allFinite() || !vector.allFinite()) return;
    const Vec3 to = from + vector;
    lines.push_back({from.cast<float>(), to.cast<float>(), colour});
    const Vec3 along = vector / size;
    const Vec3 side =
        (std::abs(along.y()) < 0.9 ? along.cross(Vec3::UnitY()) : along.cross(Vec3::UnitX())).normalized();
    for (const double sign : {-1.0, 1.0})
        lines.push_back(
            {to.cast<float>(), (to - 0.2 * size * along + sign * 0.1 * size * side).cast<float>(), colour});
}

/// A body's reach for drawing (0 for an unbounded shape).
double drawnReach(const Body& body) {
    const double reach = shapeReach(body.shape);
    return std::isfinite(reach) ? reach : 0.0;
}

const char* stageName(SoftStage stage) {
    switch (stage) {
        case SoftStage::Elements:
            return "soft elements";
        case SoftStage::Attachments:
            return "soft attachments";
        case SoftStage::Contacts:
            return "soft contacts";
        case SoftStage::ContactVelocities:
            return "soft contacts' velocity pass";
    }
    return "soft stage";
}

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
        const std::string constraint = names.constraint(c.kind, c.index, c.body0, c.body1);
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
    const double reach = largest.bodyIndex < bodies.size() ? drawnReach(bodies[largest.bodyIndex]) : 0.0;
    const double length = reach > 0.0 ? 2.0 * reach : 0.5;
    const double scale = length / largest.size;
    for (const CorrectionEntry& entry : entries) {
        if (entry.bodyIndex >= bodies.size()) continue;
        const Vec3& centre = bodies[entry.bodyIndex].x;
        const double bodyReach = shapeReach(bodies[entry.bodyIndex].shape);
        arrow(centre, scale * entry.displacement, kMoveColour, lines);
        if (std::isfinite(bodyReach)) arrow(centre, scale * bodyReach * entry.rotation, kTurnColour, lines);
    }
}

std::string VelocityEntry::describe() const {
    char text[160];
    std::snprintf(text, sizeof text, "%s changed %s by %.3g m/s", constraint.c_str(), body.c_str(),
                  velocity.norm());
    std::string out = text;
    if (normal && tangential) {
        std::snprintf(text, sizeof text, " (normal %+.3g, friction %.3g)", *normal, *tangential);
        out += text;
    }
    if (angularVelocity.norm() > 0.0) {
        std::snprintf(text, sizeof text, ", %.3g rad/s", angularVelocity.norm());
        out += text;
    }
    return out;
}

std::vector<VelocityEntry> listVelocityChanges(SceneInstance& scene) {
    std::vector<VelocityEntry> entries;
    const World& world = scene.world();
    const SubstepCorrections* corrections = world.corrections();
    if (corrections == nullptr || corrections->substep() == 0) return entries;
    const Names names(scene.registry);
    const std::span<const Body> bodies = world.bodies();
    const std::span<const ContactPair> pairs = world.contactPairs();
    const std::span<const Contact> contacts = world.contacts();
    for (const VelocityCorrection& c : corrections->velocityChanges()) {
        const std::string constraint = names.constraint(c.kind, c.index, c.body0, c.body1);
        // A contact pair's normal, from body 0 towards body 1 (contact.h): its first point's.
        std::optional<Vec3> normal;
        if (c.kind == ConstraintKind::Contact && c.index < pairs.size() && pairs[c.index].count > 0 &&
            pairs[c.index].first < contacts.size())
            normal = contacts[pairs[c.index].first].normal;
        const auto add = [&](uint32_t index, const Vec3& velocity, const Vec3& angular) {
            if (index >= bodies.size() || bodies[index].invMass == 0.0) return;
            const double size = velocity.norm() + angular.norm() * drawnReach(bodies[index]);
            if (!(size > 0.0)) return;
            VelocityEntry entry{.constraint = constraint,
                                .body = names.body(index),
                                .kind = c.kind,
                                .bodyIndex = index,
                                .velocity = velocity,
                                .angularVelocity = angular,
                                .size = size};
            if (normal) {
                // Signed as it pushes this body away from the other: Eq. 34 raises (v0 − v1)·n,
                // so away is +n for body 0 and −n for body 1.
                const double along = velocity.dot(*normal) * (index == c.body0 ? 1.0 : -1.0);
                entry.normal = along;
                entry.tangential = (velocity - velocity.dot(*normal) * *normal).norm();
            }
            entries.push_back(std::move(entry));
        };
        add(c.body0, c.velocity0, c.angularVelocity0);
        if (c.body1 != c.body0) add(c.body1, c.velocity1, c.angularVelocity1);
    }
    std::stable_sort(entries.begin(), entries.end(),
                     [](const VelocityEntry& a, const VelocityEntry& b) { return a.size > b.size; });
    return entries;
}

void drawVelocityChanges(const std::vector<VelocityEntry>& entries, const World& world,
                         std::vector<render::DebugLine>& lines) {
    if (entries.empty()) return;
    const std::span<const Body> bodies = world.bodies();
    const VelocityEntry& largest = entries.front();
    const double reach = largest.bodyIndex < bodies.size() ? drawnReach(bodies[largest.bodyIndex]) : 0.0;
    const double scale = (reach > 0.0 ? 2.0 * reach : 0.5) / largest.size;
    for (const VelocityEntry& entry : entries)
        if (entry.bodyIndex < bodies.size()) arrow(bodies[entry.bodyIndex].x, scale * entry.velocity, kVelocityColour, lines);
}

std::string SoftStageEntry::describe() const {
    const bool velocities = stage == SoftStage::ContactVelocities;
    char amount[48];
    if (velocities) std::snprintf(amount, sizeof amount, "%.3g m/s", largest);
    else std::snprintf(amount, sizeof amount, "%s", formatLength(largest).c_str());
    char text[200];
    std::snprintf(text, sizeof text, "%s of %s %s %d particle%s, up to %s", stageName(stage), softBody.c_str(),
                  velocities ? "changed" : "moved", moved, moved == 1 ? "" : "s", amount);
    return text;
}

render::Colour softStageColour(SoftStage stage) {
    switch (stage) {
        case SoftStage::Elements:
            return kMoveColour;
        case SoftStage::Attachments:
            return render::Colour(1.0f, 0.9f, 0.55f);
        case SoftStage::Contacts:
            return render::Colour(0.45f, 0.75f, 1.0f);
        case SoftStage::ContactVelocities:
            return kVelocityColour;
    }
    return kMoveColour;
}

std::vector<SoftStageEntry> listSoftCorrections(SceneInstance& scene) {
    std::vector<SoftStageEntry> entries;
    const World& world = scene.world();
    const SubstepCorrections* corrections = world.corrections();
    const SoftSystem* soft = world.softBodies();
    if (corrections == nullptr || corrections->substep() == 0 || soft == nullptr) return entries;
    const Vec3* base = soft->particlePositions().data();
    for (int s = 0; s < kSoftStages; ++s) {
        const auto stage = static_cast<SoftStage>(s);
        const std::span<const Vec3> moves = corrections->particleCorrections(stage);
        if (moves.empty()) continue;
        scene.registry.view<ecs::SoftBody>().each([&](ecs::Entity entity, const ecs::SoftBody& body) {
            const std::span<const Vec3> own = world.softBodyPositions(body.id);
            if (own.empty()) return;
            const auto first = static_cast<std::size_t>(own.data() - base);
            if (first + own.size() > moves.size()) return;
            SoftStageEntry entry{.stage = stage, .first = first, .count = own.size()};
            for (std::size_t i = first; i < first + own.size(); ++i) {
                const double size = moves[i].norm();
                if (!(size > 0.0)) continue;
                ++entry.moved;
                entry.largest = std::max(entry.largest, size);
            }
            if (entry.moved == 0) return;
            const ecs::Name* name = scene.registry.tryGet<ecs::Name>(entity);
            entry.softBody = "'" + (name ? name->value : "soft body " + std::to_string(entity.index)) + "'";
            entries.push_back(std::move(entry));
        });
    }
    return entries;
}

void drawSoftCorrections(const std::vector<SoftStageEntry>& entries, const World& world,
                         std::vector<render::DebugLine>& lines) {
    const SubstepCorrections* corrections = world.corrections();
    const SoftSystem* soft = world.softBodies();
    if (entries.empty() || corrections == nullptr || soft == nullptr) return;
    const std::span<const Vec3> positions = soft->particlePositions();
    for (const SoftStageEntry& entry : entries) {
        const std::span<const Vec3> moves = corrections->particleCorrections(entry.stage);
        if (entry.first + entry.count > moves.size() || entry.first + entry.count > positions.size() ||
            !(entry.largest > 0.0))
            continue;
        // The soft body's size: its particles' extent.
        Vec3 low = positions[entry.first];
        Vec3 high = low;
        for (std::size_t i = entry.first; i < entry.first + entry.count; ++i) {
            low = low.cwiseMin(positions[i]);
            high = high.cwiseMax(positions[i]);
        }
        const double extent = std::max((high - low).maxCoeff(), 1e-3);
        const double scale = 0.1 * extent / entry.largest;
        const render::Colour colour = softStageColour(entry.stage);
        for (std::size_t i = entry.first; i < entry.first + entry.count; ++i)
            if (moves[i].norm() > 0.0) arrow(positions[i], scale * moves[i], colour, lines);
    }
}

}  // namespace substep::view
