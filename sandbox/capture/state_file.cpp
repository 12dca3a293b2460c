#include "capture/state_file.h"

#include "capture/json_input.h"
#include "csv_writer.h"

#include <limits>

namespace substep::capture {

namespace {

constexpr double kLargest = std::numeric_limits<double>::max();

template <std::size_t N>
void appendArray(std::string& out, const std::array<double, N>& values) {
    out += '[';
    for (std::size_t i = 0; i < N; ++i) {
        if (i > 0) out += ", ";
        appendNumber(out, values[i]);
    }
    out += ']';
}

void appendField(std::string& out, const char* key, double value) {
    out += ", \"";
    out += key;
    out += "\": ";
    appendNumber(out, value);
}

template <std::size_t N>
std::array<double, N> readArray(const JsonAt& at) {
    at.requireArray(N);
    std::array<double, N> values{};
    for (std::size_t i = 0; i < N; ++i)
        values[i] = at.element(i).number(-kLargest, kLargest);
    return values;
}

/// `"key": [` ... one element per line ... `]`.
template <typename T, typename Write>
void appendList(std::string& out, const char* key, const std::vector<T>& items, Write write) {
    out += ",\n \"";
    out += key;
    out += "\": [";
    for (std::size_t i = 0; i < items.size(); ++i) {
        out += i == 0 ? "\n  " : ",\n  ";
        write(items[i]);
    }
    out += items.empty() ? "]" : "\n ]";
}

}  // namespace

std::string formatStateFile(const CaptureState& state) {
    std::string out = "{\"substep_capture_state\": 1, \"frame\": ";
    appendInteger(out, state.frame);
    appendField(out, "t", state.time);
    appendList(out, "bodies", state.bodies, [&](const BodyState& body) {
        out += "{\"name\": " + jsonQuoted(body.name) + ", \"position\": ";
        appendArray(out, body.position);
        out += ", \"orientation\": ";
        appendArray(out, body.orientation);
        out += ", \"velocity\": ";
        appendArray(out, body.velocity);
        out += ", \"angular_velocity\": ";
        appendArray(out, body.angularVelocity);
        out += '}';
    });
    appendList(out, "joints", state.joints, [&](const JointState& joint) {
        out += "{\"name\": " + jsonQuoted(joint.name);
        appendField(out, "force", joint.force);
        appendField(out, "torque", joint.torque);
        appendField(out, "error", joint.error);
        out += '}';
    });
    appendList(out, "soft_bodies", state.softBodies, [&](const SoftBodyState& soft) {
        out += "{\"name\": " + jsonQuoted(soft.name) + ", \"centre\": ";
        appendArray(out, soft.centre);
        appendField(out, "volume", soft.volume);
        out += '}';
    });
    out += "\n}\n";
    return out;
}

CaptureState parseStateFile(std::string_view text, const std::string& file) {
    const nlohmann::ordered_json document = parseJson(text, file);
    const JsonAt root(document, "", file);
    root.requireObject({"substep_capture_state", "frame", "t", "bodies", "joints", "soft_bodies"});
    root.member("substep_capture_state").integer(1, 1);
    CaptureState state;
    state.frame = root.member("frame").integer(0, std::numeric_limits<long long>::max());
    state.time = root.member("t").number(0.0, kLargest);

    const JsonAt bodies = root.member("bodies");
    bodies.requireArray();
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        const JsonAt at = bodies.element(i);
        at.requireObject({"name", "position", "orientation", "velocity", "angular_velocity"});
        state.bodies.push_back({.name = at.member("name").string(),
                                .position = readArray<3>(at.member("position")),
                                .orientation = readArray<4>(at.member("orientation")),
                                .velocity = readArray<3>(at.member("velocity")),
                                .angularVelocity = readArray<3>(at.member("angular_velocity"))});
    }
    const JsonAt joints = root.member("joints");
    joints.requireArray();
    for (std::size_t i = 0; i < joints.size(); ++i) {
        const JsonAt at = joints.element(i);
        at.requireObject({"name", "force", "torque", "error"});
        state.joints.push_back({.name = at.member("name").string(),
                                .force = at.member("force").number(-kLargest, kLargest),
                                .torque = at.member("torque").number(-kLargest, kLargest),
                                .error = at.member("error").number(-kLargest, kLargest)});
    }
    if (root.has("soft_bodies")) {
        const JsonAt softBodies = root.member("soft_bodies");
        softBodies.requireArray();
        for (std::size_t i = 0; i < softBodies.size(); ++i) {
            const JsonAt at = softBodies.element(i);
            at.requireObject({"name", "centre", "volume"});
            state.softBodies.push_back({.name = at.member("name").string(),
                                        .centre = readArray<3>(at.member("centre")),
                                        .volume = at.member("volume").number(-kLargest, kLargest)});
        }
    }
    return state;
}

}  // namespace substep::capture
