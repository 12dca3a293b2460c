/// Scene files, the `joints` reader of the loader (scene_loader_sections.h): each joint's type,
/// the keys that type uses (kJointKeys), its bodies (named in `bodies`, or the world), frames,
/// limits, drives, compliances and damping.

#include "scene/scene_loader_sections.h"

#include <algorithm>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

namespace substep::scene_loader {

namespace {

/// Bit per joint type, for the table of which keys each type uses.
constexpr unsigned bit(JointType type) {
    return 1u << static_cast<unsigned>(type);
}
constexpr unsigned kDistance = bit(JointType::Distance);
constexpr unsigned kFixed = bit(JointType::Fixed);
constexpr unsigned kHinge = bit(JointType::Hinge);
constexpr unsigned kSpherical = bit(JointType::Spherical);
constexpr unsigned kPrismatic = bit(JointType::Prismatic);
constexpr unsigned kAllJoints = kDistance | kFixed | kHinge | kSpherical | kPrismatic;
constexpr unsigned kFramed = kFixed | kHinge | kSpherical | kPrismatic;  // those with axes

struct JointKey {
    const char* key;
    unsigned types;
};

// A distance joint links two points: it has no axes. Fixed joints use their frames (axis and
// normal) as the locked relative orientation.
constexpr JointKey kJointKeys[] = {
    {"name", kAllJoints},
    {"type", kAllJoints},
    {"body0", kAllJoints},
    {"body1", kAllJoints},
    {"anchor0", kAllJoints},
    {"anchor1", kAllJoints},
    {"compliance", kAllJoints},
    {"damping", kAllJoints},
    {"collide", kAllJoints},
    {"axis0", kFramed},
    {"axis1", kFramed},
    {"normal0", kFramed},
    {"normal1", kFramed},
    {"max_distance", kDistance},
    {"limits", kHinge | kPrismatic},
    {"limit_compliance", kHinge | kPrismatic | kSpherical},
    {"target_angle", kHinge},
    {"target_velocity", kHinge},
    {"target_offset", kPrismatic},
    {"drive_compliance", kHinge | kPrismatic},
    {"swing_limit", kSpherical},
    {"twist_limits", kSpherical},
    {"twist_compliance", kSpherical},
};

struct JointTypeName {
    const char* name;
    JointType type;
};
constexpr JointTypeName kJointTypes[] = {
    {"distance", JointType::Distance},   {"fixed", JointType::Fixed},
    {"hinge", JointType::Hinge},         {"spherical", JointType::Spherical},
    {"prismatic", JointType::Prismatic},
};

std::string jointTypesText(unsigned types) {
    std::vector<std::string> names;
    for (const auto& t : kJointTypes) {
        if (types & bit(t.type)) names.push_back(t.name);
    }
    return joinList(names, " and ");
}

std::string articled(const char* typeName) {
    return std::string(typeName[0] == 'a' || typeName[0] == 'e' || typeName[0] == 'i' ? "an "
                                                                                      : "a ") +
           typeName;
}

SceneJoint parseJoint(const Validator& v, const Node& node,
                      const std::vector<std::string>& bodyNames,
                      const std::vector<NameAt>& jointNamesSoFar) {
    const ObjectReader obj(v, node, "a joint object");

    // The type decides which keys are allowed, so it comes first.
    const Node typeNode = obj.require("type", " (distance, fixed, hinge, spherical or prismatic)");
    const std::string typeText = v.string(typeNode);
    const JointTypeName* typeEntry = nullptr;
    for (const auto& t : kJointTypes) {
        if (typeText == t.name) typeEntry = &t;
    }
    if (!typeEntry) {
        v.fail(typeNode.path, "unknown joint type " + jsonQuoted(typeText) +
                                  " (expected distance, fixed, hinge, spherical or prismatic)");
    }
    const JointType type = typeEntry->type;

    std::vector<std::string> allowed;
    for (const auto& k : kJointKeys) {
        if (k.types & bit(type)) allowed.push_back(k.key);
    }
    for (const auto& item : obj.value().items()) {
        // A plain variable, not a structured binding: clang 14 cannot capture those in a lambda.
        const std::string& key = item.key();
        const auto known = std::find_if(std::begin(kJointKeys), std::end(kJointKeys),
                                        [&](const JointKey& k) { return key == k.key; });
        if (known == std::end(kJointKeys)) obj.failUnknown(key, allowed);
        if (!(known->types & bit(type))) {
            v.fail(obj.pathOf(key), "does not apply to " + articled(typeEntry->name) +
                                        " joint (only to " + jointTypesText(known->types) +
                                        " joints)");
        }
    }

    SceneJoint joint;
    JointDef& def = joint.def;
    def.type = type;

    if (auto n = obj.get("name")) {
        joint.name = v.name(*n);
        for (const auto& [other, otherPath] : jointNamesSoFar) {
            if (other == joint.name) {
                v.fail(n->path, "duplicate joint name " + jsonQuoted(joint.name) +
                                    " (already used at " + otherPath + ")");
            }
        }
    }

    // Bodies: names of bodies defined in "bodies"; omitted or "world" is the world.
    const auto readBody = [&](const char* key) -> std::string {
        const auto b = obj.get(key);
        if (!b) return "";
        std::string name = v.string(*b);
        if (name.empty())
            v.fail(b->path,
                   "must name a body (leave the key out, or say \"world\", for the world)");
        if (name == "world") return name;
        if (std::find(bodyNames.begin(), bodyNames.end(), name) == bodyNames.end()) {
            v.fail(b->path, "no body named " + jsonQuoted(name) + suggestion(name, bodyNames));
        }
        return name;
    };
    joint.body0 = readBody("body0");
    joint.body1 = readBody("body1");
    const bool world0 = joint.body0.empty() || joint.body0 == "world";
    const bool world1 = joint.body1.empty() || joint.body1 == "world";
    if (world0 && world1) {
        const std::string path = obj.has("body1")   ? obj.pathOf("body1")
                                 : obj.has("body0") ? obj.pathOf("body0")
                                                    : obj.path();
        v.fail(path, "both ends of the joint are the world: body0 or body1 must name a body");
    }
    if (!world0 && joint.body0 == joint.body1) {
        v.fail(obj.pathOf("body1"), "joins body " + jsonQuoted(joint.body1) + " to itself");
    }

    if (auto a = obj.get("anchor0")) def.anchor0 = v.vec3(*a, within(kMaxCoordinate));
    if (auto a = obj.get("anchor1")) def.anchor1 = v.vec3(*a, within(kMaxCoordinate));
    if (auto a = obj.get("axis0")) def.axis0 = v.direction(*a);
    if (auto a = obj.get("axis1")) def.axis1 = v.direction(*a);
    // Normals: not parallel to their axis, then made exactly perpendicular to it.
    const auto readNormal = [&](const char* key, const Vec3& axis) -> std::optional<Vec3> {
        const auto n = obj.get(key);
        if (!n) return std::nullopt;
        const Vec3 normal = v.direction(*n);
        const Vec3 perpendicular = normal - normal.dot(axis) * axis;
        if (perpendicular.norm() <= kParallelSine) {
            v.fail(n->path, "is parallel to the joint axis (a normal must be perpendicular to it)");
        }
        return perpendicular.normalized();
    };
    def.normal0 = readNormal("normal0", def.axis0);
    def.normal1 = readNormal("normal1", def.axis1);
    if (auto c = obj.get("compliance"))
        def.compliance = v.number(*c, nonNegativeUpTo(kMaxCompliance));

    if (auto d = obj.get("max_distance"))
        def.maxDistance = v.number(*d, nonNegativeUpTo(kMaxCoordinate));
    if (auto l = obj.get("limits")) {
        def.limits =
            type == JointType::Hinge ? v.angleRange(*l) : v.range(*l, within(kMaxCoordinate));
    }
    if (auto c = obj.get("limit_compliance"))
        def.limitCompliance = v.number(*c, nonNegativeUpTo(kMaxCompliance));
    if (auto t = obj.get("target_angle")) def.targetAngle = v.angle(*t, -kPi, kPi, "-pi", "pi");
    if (auto t = obj.get("target_velocity")) {
        if (def.targetAngle) {
            v.fail(t->path, "give target_angle (a drive) or target_velocity (a motor), not both");
        }
        def.targetVelocity = v.number(*t, within(kMaxSpeed));
    }
    if (auto t = obj.get("target_offset")) def.targetOffset = v.number(*t, within(kMaxCoordinate));
    if (auto c = obj.get("drive_compliance"))
        def.driveCompliance = v.number(*c, nonNegativeUpTo(kMaxCompliance));
    if (auto s = obj.get("swing_limit")) def.swingLimit = v.angle(*s, 0.0, kPi, "0", "pi");
    if (auto t = obj.get("twist_limits")) def.twistLimits = v.angleRange(*t);
    if (auto c = obj.get("twist_compliance"))
        def.twistCompliance = v.number(*c, nonNegativeUpTo(kMaxCompliance));

    if (auto d = obj.get("damping")) {
        const ObjectReader damping(v, *d, "an object {\"linear\": ..., \"angular\": ...}");
        damping.allowOnly({"linear", "angular"});
        if (auto l = damping.get("linear"))
            def.linearDamping = v.number(*l, nonNegativeUpTo(kMaxDamping));
        if (auto a = damping.get("angular"))
            def.angularDamping = v.number(*a, nonNegativeUpTo(kMaxDamping));
    }
    if (auto c = obj.get("collide")) def.collide = v.boolean(*c);
    return joint;
}

}  // namespace

void readJoints(const Node& node, SceneReading& reading) {
    const Validator& v = reading.validator;
    std::vector<std::string> bodyNames;
    for (const auto& [name, path] : reading.bodyNames)
        bodyNames.push_back(name);
    if (!node.value.is_array()) {
        v.fail(node.path, "must be an array of joints, got " + describe(node.value));
    }
    for (std::size_t i = 0; i < node.value.size(); ++i) {
        const Node element{node.value[i], elementPath(node.path, i)};
        reading.scene.joints.push_back(parseJoint(v, element, bodyNames, reading.jointNames));
        if (!reading.scene.joints.back().name.empty()) {
            reading.jointNames.push_back(
                {reading.scene.joints.back().name, memberPath(element.path, "name")});
        }
    }
}

}  // namespace substep::scene_loader
