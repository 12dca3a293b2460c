// The drop of the rolling ball sculpture (sandbox/scenes/rolling_balls.cpp): after the helix the
// cage ends in a pipe that turns the marbles straight down onto a see-saw switch; the switch
// sends them alternately into a branch on either side, and both branches run round to a funnel
// whose spout pipe leads back into the cage. Issue 15: "a drop through a funnel ... at least one
// clever mechanism (a see-saw or tipping switch that sends marbles alternately left and right,
// driven only by contacts and a hinge with limits)".

#include "scenes/rolling_balls_track.h"

#include "physics/collision/mesh_collider.h"

#include <string>

namespace substep::scenes::rolling_balls {

namespace {

/// A quarter circle from `start` heading `from` to heading `to` (unit, perpendicular), a point
/// every 15°, without the start.
void quarterBend(const Vec3& start, const Vec3& from, const Vec3& to, double radius,
                 std::vector<Vec3>& out) {
    const Vec3 centre = start + radius * to;
    for (int i = 1; i <= 6; ++i) {
        const double a = M_PI / 2 * i / 6;
        out.push_back(centre + radius * (std::sin(a) * from - std::cos(a) * to));
    }
}

}  // namespace

/// A framed point of a line that may run vertically: the frame's side is `across`.
PathPoint framedAcross(const Vec3& position, const Vec3& tangent, const Vec3& across) {
    const Vec3 side = (across - across.dot(tangent) * tangent).normalized();
    return {position, side, side.cross(tangent).normalized()};
}

DropLayout layDrop(const Vec3& cageEnd, double heading) {
    DropLayout d;
    d.heading = heading;
    d.along = Vec3(std::cos(heading), 0.0, -std::sin(heading));
    d.across = Vec3::UnitY().cross(d.along);
    const Vec3 down = -Vec3::UnitY();
    // The exit pipe starts a little inside the cage, so the marble is held all the way.
    d.exitPipe.push_back(cageEnd - 0.02 * d.along);
    d.exitPipe.push_back(cageEnd);
    quarterBend(cageEnd, d.along, down, kExitBend, d.exitPipe);
    const Vec3 exit = d.exitPipe.back() + kPipeDown * down;
    d.exitPipe.push_back(exit);
    // The marble leaves the pipe against its outer wall (pressed there round the bend): the
    // switch is centred under it.
    d.pivot = exit + kPivotBelowExit * down + (kPipeRadius - kMarbleRadius) * d.along;
    // Each branch: out across the track, a quarter turn along it, a short straight, a quarter
    // turn back in, and in over the funnel's rim, where it ends above the hole's axis.
    double reachAlong = 0.0;
    for (int k = 0; k < 2; ++k) {
        const double sign = k == 0 ? -1.0 : 1.0;
        const Vec3 start = d.pivot + sign * (kBeamHalf + 0.005) * d.across - kBranchDrop * Vec3::UnitY();
        Turtle turtle(start, heading + sign * M_PI / 2, kBranchSlope);
        std::vector<PathPoint> line{Turtle::framed(start, turtle.direction())};
        turtle.run(kBranchCatch, 0.0, kBranchSlope, line);
        turtle.run(kBranchBend * M_PI / 2, -sign / kBranchBend, kBranchSlope, line);
        turtle.run(kBranchStraight, 0.0, kBranchSlope, line);
        turtle.run(kBranchBend * M_PI / 2, -sign / kBranchBend, kBranchSlope, line);
        const double outwards = (turtle.position() - d.pivot).dot(d.across) * sign;
        turtle.run(outwards - kFunnelRim + 0.01, 0.0, kBranchSlope, line);
        reachAlong = (turtle.position() - d.pivot).dot(d.along);
        d.branches[k] = std::move(line);
    }
    const Vec3 branchEnd = d.branches[0].back().position;
    const Vec3 rimCentre(d.pivot.x(), branchEnd.y() - kRimBelowBranch, d.pivot.z());
    d.hole = rimCentre + reachAlong * d.along -
             kFunnelSteepness * (kFunnelRim - kFunnelHole) * Vec3::UnitY();
    // The spout: a pipe from the hole straight down, then turning along the track.
    d.spoutPipe.push_back(d.hole);
    d.spoutPipe.push_back(d.hole + kSpoutDown * down);
    const Vec3 slope = (d.along - kReturnSlope * Vec3::UnitY()).normalized();
    const Vec3 turnTo = (slope - slope.dot(down) * down).normalized();  // = along
    quarterBend(d.spoutPipe.back(), down, turnTo, kSpoutBend, d.spoutPipe);
    d.spoutPipe.push_back(d.spoutPipe.back() + 0.03 * (d.along - kReturnSlope * Vec3::UnitY()));
    return d;
}

/// A funnel: a cone of triangles from the rim down to the hole, facing in and up.
std::shared_ptr<const TriangleMesh> funnelMesh(const DropLayout& d) {
    constexpr int kSides = 32;
    const double height = kFunnelSteepness * (kFunnelRim - kFunnelHole);
    auto mesh = std::make_shared<TriangleMesh>();
    for (int i = 0; i < kSides; ++i) {
        const double a = 2.0 * M_PI * i / kSides;
        const Vec3 radial = std::cos(a) * d.along + std::sin(a) * d.across;
        mesh->vertices.push_back(d.hole + kFunnelHole * radial);
        mesh->vertices.push_back(d.hole + kFunnelRim * radial + height * Vec3::UnitY());
    }
    for (int i = 0; i < kSides; ++i) {
        const int j = (i + 1) % kSides;
        const int lo0 = 2 * i, hi0 = 2 * i + 1, lo1 = 2 * j, hi1 = 2 * j + 1;
        // Counter-clockwise seen from the axis (inside): the front faces in and up.
        mesh->triangles.push_back({lo0, hi0, hi1});
        mesh->triangles.push_back({lo0, hi1, lo1});
    }
    // Turn them to face the axis, whichever way the frame above winds.
    const auto& v = mesh->vertices;
    const Vec3 normal = (v[1] - v[0]).cross(v[3] - v[0]);
    if (normal.dot(d.hole - v[0]) < 0.0)
        for (auto& t : mesh->triangles) std::swap(t[1], t[2]);
    return mesh;
}

/// The switch: a see-saw across the track under the exit pipe, hinged along the track with its
/// tilt limited either way, and a fin standing on it over the hinge. The fin leans with the beam
/// towards the low side, so a marble falling onto it is turned to the high side, where its weight
/// tips the beam over and it rolls off that end; the beam stays down on that side (the fin holds
/// its centre of mass above the hinge) and leans the fin over for the next marble, which goes
/// the other way. Nothing but contacts and the hinge's limits moves it.
void addSwitch(SceneDescription& scene, const DropLayout& d) {
    Mat3 frame;
    frame << d.across, Vec3::UnitY(), d.along;  // the parts' x across, y up, z along the track
    const Quat orientation = Quat(Eigen::AngleAxisd(kSwitchTilt, d.along)) * Quat(frame);
    const auto part = [&](const std::string& name, const Vec3& size, const Vec3& offset) {
        scene.bodies.push_back({name,
                                BodyDef{.shape = boxShape(size),
                                        .position = d.pivot + orientation * offset,
                                        .orientation = orientation,
                                        .staticFriction = kMarbleFriction,
                                        .dynamicFriction = kMarbleFriction,
                                        .collisionGroup = kArmGroup,
                                        .collisionMask = ~kWireGroup},
                                Vec3(0.25, 0.45, 0.8)});
        if (name == "switch_beam") return;
        // Welded to the beam (the engine's bodies have one shape each).
        addJoint(scene, name + "_weld", "switch_beam", name,
                 JointDef{.type = JointType::Fixed, .anchor0 = offset, .anchor1 = Vec3::Zero()});
    };
    const double top = 0.5 * kBeamThickness;
    part("switch_beam", Vec3(2.0 * kBeamHalf, kBeamThickness, kPartWidth), Vec3::Zero());
    addJoint(scene, "switch_hinge", "", "switch_beam",
             JointDef{.type = JointType::Hinge,
                      .anchor0 = d.pivot,
                      .axis0 = d.along,
                      .axis1 = Vec3::UnitZ(),
                      .normal0 = Vec3::UnitY(),
                      .normal1 = Vec3::UnitY(),
                      .limits = Range{-kSwitchTilt, kSwitchTilt},
                      .angularDamping = kSwitchDamping});
    part("switch_fin", Vec3(kFinThickness, kFinHeight, kPartWidth), Vec3(0.0, top + 0.5 * kFinHeight, 0.0));
    // Walls before and behind the switch: a marble knocked along the track by the one behind
    // it stays over the branches' mouths.
    Mat3 wallFrame;
    wallFrame << d.across, Vec3::UnitY(), d.along;
    for (const double side : {-1.0, 1.0})
        scene.bodies.push_back(
            {side < 0 ? "switch_wall_0" : "switch_wall_1",
             BodyDef{.shape = boxShape(Vec3(2.0 * kWallHalf, kWallHeight, 0.004)),
                     .type = BodyType::Static,
                     .position = d.pivot + side * (kBranchMouth + 0.003) * d.along +
                                 (0.045 - 0.5 * kWallHeight) * Vec3::UnitY(),
                     .orientation = Quat(wallFrame),
                     .staticFriction = kMarbleFriction,
                     .dynamicFriction = kMarbleFriction},
             Vec3(0.8, 0.85, 0.9)});
    // Lips along both edges make the beam a channel: the marble leaves its end straight across
    // the track, whatever it kept of its speed along the track, and lands in the branch's middle.
    for (const double side : {-1.0, 1.0})
        part(side < 0 ? "switch_lip_0" : "switch_lip_1", Vec3(2.0 * kBeamHalf, kLipHeight, kLipThickness),
             Vec3(0.0, top + 0.5 * kLipHeight, side * 0.5 * (kPartWidth + kLipThickness)));
}

/// A guard wire of a branch (corner 2 or 3): over the catch it starts low and wide and closes
/// in to its corner, a mouth that turns a marble landing off the middle onto the lower wires.
std::shared_ptr<const SplineTube> branchGuardWire(const std::vector<PathPoint>& line, int corner) {
    const double side = corner == 2 ? -1.0 : 1.0;
    const double offset = kCageRadius / std::sqrt(2.0);
    std::vector<Vec3> points;
    for (size_t i = 0; i < line.size(); ++i) {
        const double u = std::min(1.0, static_cast<double>(i) / kBranchGuardFrom);
        const double out = kBranchMouth + (offset - kBranchMouth) * u;
        points.push_back(line[i].position + side * out * line[i].side + offset * u * line[i].up);
    }
    return makeSplineTube(std::move(points), kWireRadius, false);
}

}  // namespace substep::scenes::rolling_balls
