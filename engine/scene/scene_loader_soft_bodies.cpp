/// Scene files, the `soft_bodies` reader of the loader (scene_loader_sections.h): each soft
/// body's name, lattice (box or tyre), pose, velocity, material and surface properties, and its
/// attachments to bodies named in `bodies`.

#include "scene/scene_loader_sections.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace substep::scene_loader {

namespace {

/// Cells per lattice direction, and elements in one scene (sanity: the solver's cost and memory).
constexpr int kMaxCells = 64;
constexpr std::int64_t kMaxSceneElements = 100000;
/// A tyre closes on itself around its axis: fewer than 3 cells around enclose no ring.
constexpr int kMinTyreCellsAround = 3;

/// [n0, n1, n2], each an integer in [lo, kMaxCells]; the path of a bad one names its element.
std::array<int, 3> readCells(const Validator& v, const Node& node, const int (&lo)[3], const char* what) {
    if (!node.value.is_array() || node.value.size() != 3) {
        v.fail(node.path, std::string("must be ") + what + ", got " + describe(node.value));
    }
    std::array<int, 3> cells{};
    for (std::size_t i = 0; i < 3; ++i) cells[i] = v.integer({node.value[i], elementPath(node.path, i)}, lo[i], kMaxCells);
    return cells;
}

/// The lattice: `type` and the sizes and cells it uses; returns the rest volume (m³).
double readLattice(const Validator& v, const ObjectReader& obj, SoftBodyDef& def) {
    const Node typeNode = obj.require("type", " (\"box\" or \"tyre\")");
    const std::string type = v.string(typeNode);
    if (type == "box") {
        def.type = SoftBodyType::Box;
        def.size = v.vec3(obj.require("size", " (full extents [x, y, z] in m)"), sizeUpTo(kMaxSize));
        def.cells = readCells(v, obj.require("cells", " ([nx, ny, nz], each 1-64)"), {1, 1, 1},
                              "an array [nx, ny, nz] of cell counts");
        return def.size.prod();
    }
    if (type == "tyre") {
        def.type = SoftBodyType::Tyre;
        def.outerRadius = v.number(obj.require("outer_radius", " (m)"), sizeUpTo(kMaxSize));
        const Node inner = obj.require("inner_radius", " (m, below outer_radius)");
        def.innerRadius = v.number(inner, sizeUpTo(kMaxSize));
        if (def.innerRadius >= def.outerRadius) {
            v.fail(inner.path, "must be < outer_radius (" + formatNumber(def.outerRadius) + "), got " +
                                   formatNumber(def.innerRadius));
        }
        def.width = v.number(obj.require("width", " (m, along the tyre's local y axis)"), sizeUpTo(kMaxSize));
        def.cells = readCells(v, obj.require("cells", " ([around, radial, across]; around 3-64, the others 1-64)"),
                              {kMinTyreCellsAround, 1, 1}, "an array [around, radial, across] of cell counts");
        return kPi * (def.outerRadius * def.outerRadius - def.innerRadius * def.innerRadius) * def.width;
    }
    v.fail(typeNode.path, "unknown soft body type " + jsonQuoted(type) + " (expected \"box\" or \"tyre\")");
}

/// One entry of `attach`: the body's name (checked against `bodyNames`) and the attachment.
SoftAttachmentDef readAttachment(const Validator& v, const Node& node, const std::vector<NameAt>& bodyNames,
                                 SoftBodyType type, std::string& bodyName) {
    const ObjectReader obj(v, node, "an object {\"body\": NAME, \"particles\": \"all\", \"compliance\": 0}");
    obj.allowOnly({"body", "particles", "compliance"});
    const Node body = obj.require("body", " (the name of a body in `bodies`)");
    bodyName = v.string(body);
    bool known = false;
    for (const NameAt& named : bodyNames) known = known || named.name == bodyName;
    if (!known) {
        v.fail(body.path, bodyName == "world"
                              ? std::string("a soft body attaches to a body, not to the world (use a static body)")
                              : "unknown body " + jsonQuoted(bodyName));
    }
    SoftAttachmentDef attachment;
    if (auto p = obj.get("particles")) {
        const std::string particles = v.string(*p);
        if (particles == "all") {
            attachment.particles = SoftAttachmentParticles::All;
        } else if (particles == "inner") {
            if (type != SoftBodyType::Tyre) v.fail(p->path, "\"inner\" is a tyre's innermost layer; a box has none");
            attachment.particles = SoftAttachmentParticles::Inner;
        } else if (particles == "below") {
            attachment.particles = SoftAttachmentParticles::Below;
        } else {
            v.fail(p->path, "must be \"all\", \"inner\" or \"below\", got " + describe(p->value));
        }
    }
    if (auto c = obj.get("compliance")) attachment.compliance = v.number(*c, nonNegativeUpTo(kMaxCompliance));
    return attachment;
}

SceneSoftBody parseSoftBody(const Validator& v, const Node& node, const SceneReading& reading,
                            const std::vector<NameAt>& softNamesSoFar) {
    const ObjectReader obj(v, node, "a soft body object");
    obj.allowOnly({"name", "type", "size", "outer_radius", "inner_radius", "width", "cells", "position",
                   "orientation", "velocity", "angular_velocity", "density", "compliance", "volume_compliance",
                   "damping", "friction", "restitution", "particle_radius", "collide", "attach"});
    SceneSoftBody softBody;
    SoftBodyDef& def = softBody.def;

    if (auto n = obj.get("name")) {
        softBody.name = v.name(*n);
        // Soft bodies' CSV columns (NAME.x, ...) share a namespace with bodies'.
        const auto clash = [&](const std::vector<NameAt>& names, const char* kind) {
            for (const auto& [other, otherPath] : names) {
                if (other == softBody.name) {
                    v.fail(n->path, std::string("duplicate ") + kind + " name " + jsonQuoted(softBody.name) +
                                        " (already used at " + otherPath + ")");
                }
            }
        };
        clash(reading.bodyNames, "body");
        clash(softNamesSoFar, "soft body");
        if (softBody.name == "world") v.fail(n->path, "\"world\" is reserved: joints use it for the world itself");
    }

    const double volume = readLattice(v, obj, def);
    // Keys of the other lattice type are mistakes, not silently ignored values.
    for (const char* key : def.type == SoftBodyType::Box
                               ? std::vector<const char*>{"outer_radius", "inner_radius", "width"}
                               : std::vector<const char*>{"size"}) {
        if (obj.has(key)) {
            v.fail(obj.pathOf(key), std::string("a ") + (def.type == SoftBodyType::Box ? "box" : "tyre") +
                                        " soft body does not use " + key);
        }
    }

    if (auto p = obj.get("position")) def.position = v.vec3(*p, within(kMaxCoordinate));
    if (auto q = obj.get("orientation")) def.orientation = v.quaternion(*q);
    if (auto vel = obj.get("velocity")) def.velocity = v.vec3(*vel, within(kMaxSpeed));
    if (auto w = obj.get("angular_velocity")) def.angularVelocity = v.vec3(*w, within(kMaxSpeed));
    if (auto d = obj.get("density")) def.density = v.number(*d, positiveUpTo(kMaxDensity));
    if (def.density * volume > kMaxMass) {
        v.fail(obj.has("density") ? obj.pathOf("density") : obj.pathOf("type"),
               "density " + formatNumber(def.density) + " kg/m³ gives this soft body a mass of " +
                   formatNumber(def.density * volume) + " kg, above the 1e+09 kg sanity bound");
    }
    if (auto c = obj.get("compliance")) def.compliance = v.number(*c, nonNegativeUpTo(kMaxCompliance));
    if (auto c = obj.get("volume_compliance")) {
        def.preserveVolume = true;
        def.volumeCompliance = v.number(*c, nonNegativeUpTo(kMaxCompliance));
    }
    if (auto d = obj.get("damping")) def.damping = v.number(*d, nonNegativeUpTo(kMaxDamping));
    if (auto f = obj.get("friction")) {
        const ObjectReader friction(v, *f, "an object {\"static\": μs, \"dynamic\": μd}");
        friction.allowOnly({"static", "dynamic"});
        if (auto s = friction.get("static")) def.staticFriction = v.number(*s, nonNegativeUpTo(kMaxFriction));
        if (auto d = friction.get("dynamic")) def.dynamicFriction = v.number(*d, nonNegativeUpTo(kMaxFriction));
    }
    if (auto e = obj.get("restitution")) def.restitution = v.number(*e, closed(0.0, 1.0));
    if (auto r = obj.get("particle_radius")) def.particleRadius = v.number(*r, sizeUpTo(kMaxSize));
    if (auto c = obj.get("collide")) def.collide = v.boolean(*c);

    if (auto a = obj.get("attach")) {
        if (!a->value.is_array()) v.fail(a->path, "must be an array of attachments, got " + describe(a->value));
        for (std::size_t i = 0; i < a->value.size(); ++i) {
            std::string bodyName;
            def.attachments.push_back(
                readAttachment(v, {a->value[i], elementPath(a->path, i)}, reading.bodyNames, def.type, bodyName));
            softBody.attachBodies.push_back(std::move(bodyName));
        }
    }
    return softBody;
}

}  // namespace

void readSoftBodies(const Node& node, SceneReading& reading) {
    const Validator& v = reading.validator;
    if (!node.value.is_array()) v.fail(node.path, "must be an array of soft bodies, got " + describe(node.value));
    std::vector<NameAt> softNames;
    std::int64_t elements = 0;
    for (std::size_t i = 0; i < node.value.size(); ++i) {
        const Node element{node.value[i], elementPath(node.path, i)};
        SceneSoftBody softBody = parseSoftBody(v, element, reading, softNames);
        const std::array<int, 3>& cells = softBody.def.cells;
        elements += std::int64_t{cells[0]} * cells[1] * cells[2];
        if (elements > kMaxSceneElements) {
            v.fail(memberPath(element.path, "cells"),
                   "the scene's soft bodies would have " + std::to_string(elements) +
                       " elements, above the sanity bound of 100000 per scene");
        }
        if (!softBody.name.empty()) softNames.push_back({softBody.name, memberPath(element.path, "name")});
        reading.scene.softBodies.push_back(std::move(softBody));
    }
}

}  // namespace substep::scene_loader
