/// Scene files, the `bodies` reader of the loader (scene_loader_sections.h): each body's name,
/// shape (scene_loader_shapes.h), mass or density, pose, velocities and surface properties.

#include "scene/scene_loader_sections.h"
#include "scene/scene_loader_shapes.h"

#include "physics/mass_properties.h"

#include <string>
#include <vector>

namespace substep::scene_loader {

namespace {

SceneBody parseBody(const Validator& v, const Node& node, const std::vector<NameAt>& namesSoFar) {
    const ObjectReader obj(v, node, "a body object");
    obj.allowOnly({"name", "shape", "static", "mass", "density", "position", "orientation",
                   "velocity", "angular_velocity", "friction", "restitution", "collide"});
    SceneBody body;
    BodyDef& def = body.def;

    if (auto n = obj.get("name")) {
        body.name = v.name(*n);
        if (body.name == "world") {
            v.fail(n->path, "\"world\" is reserved: joints use it for the world itself");
        }
        for (const auto& [other, otherPath] : namesSoFar) {
            if (other == body.name) {
                v.fail(n->path, "duplicate body name " + jsonQuoted(body.name) +
                                    " (already used at " + otherPath + ")");
            }
        }
    }

    bool isStatic = false;
    if (auto s = obj.get("static")) isStatic = v.boolean(*s);
    def.type = isStatic ? BodyType::Static : BodyType::Dynamic;
    def.shape = readShape(
        v, obj.require("shape", " (e.g. {\"type\": \"sphere\", \"radius\": 0.5})"), isStatic);

    // Mass: static bodies have none; dynamic ones take a mass or a density, not both.
    const auto mass = obj.get("mass");
    const auto density = obj.get("density");
    if (isStatic) {
        if (mass)
            v.fail(mass->path, "a static body has no mass (remove it, or make the body dynamic)");
        if (density)
            v.fail(density->path,
                   "a static body has no density (remove it, or make the body dynamic)");
    }
    if (mass && density) v.fail(density->path, "give mass or density, not both");
    if (mass) {
        def.mass = v.number(*mass, {.lo = 0, .hi = kMaxMass, .loOpen = true, .hiSanity = true,
                                    .least = kMinMass});
    }
    if (density) def.density = v.number(*density, positiveUpTo(kMaxDensity));
    if (!isStatic && !mass) {
        const double derived = def.density * shapeVolume(def.shape);
        if (derived > kMaxMass) {
            v.fail(density ? density->path : obj.pathOf("shape"),
                   "density " + formatNumber(def.density) + " kg/m³ gives this shape a mass of " +
                       formatNumber(derived) + " kg, above the 1e+09 kg sanity bound");
        }
        if (derived < kMinMass && shapeVolume(def.shape) > 0.0) {
            v.fail(density ? density->path : obj.pathOf("shape"),
                   "density " + formatNumber(def.density) + " kg/m³ gives this shape a mass of " +
                       formatNumber(derived) + " kg, below the 1e-06 kg lower bound (give a mass)");
        }
    }
    if (!isStatic && shapeVolume(def.shape) > 0.0) {
        // The moments follow from the mass and the shape; each must stay far from underflow
        // (a 1 mg needle of 0.1 mm is 5e-15 kg m² about its axis).
        const MassProperties properties =
            mass ? withMass(shapeMassProperties(def.shape, 1.0), def.mass)
                 : shapeMassProperties(def.shape, def.density);
        const double smallest = principalFrame(properties.inertia).moments.minCoeff();
        if (!(smallest >= kMinInertia)) {
            v.fail(mass ? mass->path : obj.pathOf("shape"),
                   "gives a principal moment of inertia of " + formatNumber(smallest) +
                       " kg m², below the 1e-15 kg m² lower bound (a larger shape or mass)");
        }
    }

    const bool isPlane = def.shape.type == ShapeType::Plane;
    if (auto p = obj.get("position")) {
        def.position = v.vec3(*p, within(kMaxCoordinate));
        if (isPlane && !def.position.isZero(0.0)) {
            v.fail(p->path,
                   "a plane is placed by its normal and offset (world coordinates), not by "
                   "a position");
        }
    }
    if (auto q = obj.get("orientation")) {
        def.orientation = v.quaternion(*q);
        if (isPlane && def.orientation.vec().norm() > kDirectionEpsilon) {
            v.fail(q->path,
                   "a plane is placed by its normal and offset (world coordinates), not by "
                   "an orientation");
        }
    }
    if (auto vel = obj.get("velocity")) {
        def.velocity = v.vec3(*vel, within(kMaxSpeed));
        if (isStatic && !def.velocity.isZero(0.0)) v.fail(vel->path, "a static body does not move");
    }
    if (auto w = obj.get("angular_velocity")) {
        def.angularVelocity = v.vec3(*w, within(kMaxSpeed));
        if (isStatic && !def.angularVelocity.isZero(0.0))
            v.fail(w->path, "a static body does not move");
    }

    if (auto f = obj.get("friction")) {
        const ObjectReader friction(v, *f, "an object {\"static\": μs, \"dynamic\": μd}");
        friction.allowOnly({"static", "dynamic"});
        if (auto s = friction.get("static"))
            def.staticFriction = v.number(*s, nonNegativeUpTo(kMaxFriction));
        if (auto d = friction.get("dynamic"))
            def.dynamicFriction = v.number(*d, nonNegativeUpTo(kMaxFriction));
    }
    if (auto e = obj.get("restitution")) def.restitution = v.number(*e, closed(0.0, 1.0));
    if (auto c = obj.get("collide")) def.collide = v.boolean(*c);
    return body;
}

}  // namespace

void readBodies(const Node& node, SceneReading& reading) {
    const Validator& v = reading.validator;
    if (!node.value.is_array()) {
        v.fail(node.path, "must be an array of bodies, got " + describe(node.value));
    }
    for (std::size_t i = 0; i < node.value.size(); ++i) {
        const Node element{node.value[i], elementPath(node.path, i)};
        reading.scene.bodies.push_back(parseBody(v, element, reading.bodyNames));
        if (!reading.scene.bodies.back().name.empty()) {
            reading.bodyNames.push_back(
                {reading.scene.bodies.back().name, memberPath(element.path, "name")});
        }
    }
}

}  // namespace substep::scene_loader
