// Paper Figs. 1 and 14 and section 4: "an attempt to reproduce the fascinating sculptures of
// David Morrell ... In certain elements such as the spring shown in Figure 14 the marbles perform
// a quarter turn in a single time step. Simulating such fast curved motions requires substepping
// and the use of current constraint normals for each projection." Table 1: 10 substeps, 15 ms.
//
// One circuit: a cage of four wires (spline tubes, paper 3.5's curved geometry) around a common
// centre line. The two lower wires are the track a marble rolls on, the two upper ones the guard
// wires that keep it in where it flies (the plunge, the spring, the lift); over the top of the
// lift the cage comes back turned over, so each wire changes corner there (cageWire). From the
// top of the lift the track curves away, plunges into the spring (a coil of 16 mm radius where a
// marble at 1.8 m/s turns by about 100° per frame), leaves it into a wide helix and ends in the
// drop (rolling_balls_drop.cpp): a pipe turns the marbles down onto a see-saw switch that sends
// them alternately into a left and a right branch, both of which end over a funnel; its spout
// pipe leads back into the cage, which runs round two curves and a U-turn back to the foot of
// the lift, where the marbles queue.
// The lift is a paddle wheel: eight arms, each on its own motor-driven hinge about the same
// axle, sweep through the lift's half circle of track and push one marble each up to the top
// (a collision filter keeps the arms and the wires apart, so the arms pass between the wires).
// An arm can carry two or three marbles, which would reach the switch 35 ms apart, before its
// beam has tipped, and follow each other: a gate at the head of the plunge, a star wheel turned
// by its own hinge motor, lets one marble through per spoke, 0.26 s apart.
// Nothing is moved by the script: the arms and the gate are dynamic bodies turned by their hinge
// motors, the switch only by the marbles and its hinge's limits, the marbles only by contacts and
// gravity.
//
// The script reads the marbles once per frame (progress along the centre line, searched near
// the previous frame's place: laps, marbles on the track, speed and turn per frame in the
// spring) and changes components only where a knob asks (velocity pass, lift speed, marble count).

#include "scenes/rolling_balls_track.h"

#include "ecs/components.h"

#include "physics/collision/mesh_collider.h"
#include "physics/collision/spline_tube.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace substep::scenes {

namespace {

using namespace rolling_balls;

// The lift: a half circle of track in the plane z = 0 around the axle, swept by the arms.
const Vec3 kAxle(0.0, 0.9, 0.0);
constexpr double kLiftRadius = 0.6;  ///< m: the track's centre line around the axle
constexpr int kArms = 8;
constexpr double kArmInner = 0.05;            ///< m from the axle
constexpr double kArmOuter = kLiftRadius + kCageRadius + 0.01;
constexpr double kArmThickness = 0.012;       ///< m, along the arm's motion
constexpr double kArmWidth = 0.024;           ///< m, along the axle
constexpr double kArmMass = 0.1;              ///< kg
constexpr double kDefaultLiftSpeed = 1.2;     ///< rad/s
/// The arms' motors give way (rad per N·m) rather than crush a marble against the wires: lifting
/// three marbles (0.36 N·m) lags by 1°, a marble jammed sideways is passed over.
constexpr double kLiftCompliance = 0.05;
constexpr double kLiftDamping = 2.0;          ///< 1/s: the sprung arms settle

// The spring (Fig. 14): a coil of 3 turns, the centre line 16 mm from its axis.
constexpr double kSpringRadius = 0.016;
constexpr double kSpringEase = 0.04;  ///< m of clothoid into and out of the coil
constexpr double kSpringTurns = 3.0;
constexpr double kSpringSlope = 0.4;  ///< drop per horizontal metre: a pitch of 40 mm

// The gate: a star wheel of four bars (eight spokes 45° apart) beside the head of the plunge,
// turned by a hinge motor, its spokes sweeping the track at the marbles' centres. Between two
// spokes there is room for one marble: the spoke behind it swings in between it and the next,
// which waits for the following pocket, so marbles lifted together by one arm leave the gate a
// pocket apart. (A free wheel the marbles turn themselves stalls on the gentle slope here.)
// With six spokes 60° apart the pocket held a marble and a half: the entering spoke's tip met
// the next marble, queued against the held one, on its uphill flank and pushed it sideways
// into the far wires while the drive's target ran on, and it pressed up to 4.4 mm into the
// marble within 10 s (10 mm within 120 s). A sphere's contact normal passes through its
// centre, so no tip shape turns that push uphill; 45° apart, the tip meets the queued marble
// on its downhill flank and pushes it back up the track (0.7 mm within 10 s).
constexpr int kGateBars = 4;
constexpr double kGateHubOffset = 0.035;  ///< m beside the centre line
constexpr double kGateSpoke = 0.05;       ///< m from the hub to a spoke's end
constexpr double kGateBarMass = 0.05;     ///< kg
constexpr double kGateSpeed = 3.0;        ///< rad/s: a pocket every 0.26 s (2π / 8 / 3)
constexpr double kGateCompliance = 0.5;  ///< rad per N·m: a spoke swinging in onto a marble gives way a little
constexpr size_t kGateInto = 5;           ///< control points into the plunge (10 cm)

/// The circuit's centre line, in running order from the top of the lift, with where the spring
/// is along it (indices into points).
struct SculpturePath {
    std::vector<PathPoint> points;
    std::vector<double> distance;  ///< arc length from points[0] (m)
    double length = 0.0;           ///< of the closed loop (m)
    size_t springBegin = 0;
    size_t springEnd = 0;
    size_t gate = 0;       ///< where the gate stands
    size_t liftBegin = 0;  ///< the foot of the lift: the lift runs from here to the end
    /// The drop (dropBegin to dropEnd): the cage ends, a pipe turns the marbles down onto the
    /// switch, a branch on each side carries them to the funnel, whose spout pipe leads back
    /// into the cage. The centre line runs through the switch and the funnel.
    size_t dropBegin = 0;
    size_t dropEnd = 0;
    DropLayout drop;
};

SculpturePath buildPath() {
    SculpturePath path;
    std::vector<PathPoint>& points = path.points;
    const Vec3 top = kAxle + Vec3(0.0, kLiftRadius, 0.0);
    const Vec3 foot = kAxle - Vec3(0.0, kLiftRadius, 0.0);

    // From the top of the lift, heading −x, curving away from the wheel's plane.
    Turtle turtle(top, M_PI);
    points.push_back(Turtle::framed(top, turtle.direction()));
    turtle.run(0.2 * M_PI / 2, -1.0 / 0.2, 0.05, points);  // a quarter turn to −z
    path.gate = points.size() - 1 + kGateInto;
    turtle.run(0.3, 0.0, 0.5, points);                    // the plunge: steepening to 27°
    turtle.run(0.45, 0.0, kSpringSlope, points);          // and easing into the spring
    path.springBegin = points.size() - 1;
    // Into and out of the coil along clothoids of kSpringEase each, which turn by half as much
    // as the same length of coil.
    turtle.ease(kSpringEase, -1.0 / kSpringRadius, kSpringSlope, points);
    turtle.run(2.0 * M_PI * kSpringRadius * kSpringTurns - kSpringEase, -1.0 / kSpringRadius,
               kSpringSlope, points);
    turtle.ease(kSpringEase, 0.0, kSpringSlope, points);
    path.springEnd = points.size() - 1;
    turtle.run(0.15, 0.0, 0.12, points);
    turtle.run(2.0 * M_PI * 0.15 * 1.25, 1.0 / 0.15, 0.12, points);  // the helix, out to −x
    turtle.run(0.1, 0.0, 0.05, points);
    // The drop: the centre line goes down the exit pipe to the switch, along to the funnel
    // (the marbles take a branch on either side of it) and down the spout.
    path.dropBegin = points.size() - 1;
    path.drop = layDrop(turtle.position(), turtle.heading());
    const DropLayout& drop = path.drop;
    const auto follow = [&](const Vec3& to) {
        const Vec3 from = points.back().position;
        const int steps = std::max(1, static_cast<int>(std::ceil((to - from).norm() / kSampleSpacing)));
        for (int i = 1; i <= steps; ++i) {
            const Vec3 x = from + (to - from) * (static_cast<double>(i) / steps);
            points.push_back(framedAcross(x, (to - from).normalized(), -drop.across));
        }
    };
    for (size_t i = 2; i < drop.exitPipe.size(); ++i) follow(drop.exitPipe[i]);
    follow(drop.pivot);
    follow(Vec3(drop.hole.x(), drop.pivot.y(), drop.hole.z()));
    for (const Vec3& x : drop.spoutPipe) follow(x);
    path.dropEnd = points.size() - 1;
    turtle = Turtle(drop.spoutPipe.back(), drop.heading, kReturnSlope);
    // Back to the foot of the lift round the front: a left turn to +z, a wide left U-turn to
    // −z and a last right turn onto the line to the foot, heading +x. The drop is shared evenly
    // over this part.
    constexpr double kCurve = 0.2;       // m, the quarter turns
    constexpr double kUTurn = 0.4;       // m, the U-turn's radius
    constexpr double kFinalRun = 0.4;    // m, straight along −z before the last turn
    // m, straight in the arms' plane to the foot: the track enters that plane beyond the arms'
    // reach, so they meet the queue only face on.
    constexpr double kFootRun = 0.25;
    const Vec3 here = turtle.position();
    const double alongX = here.x() - foot.x() + 2.0 * kUTurn + kFootRun;
    const double alongZ = foot.z() + kFinalRun - here.z();
    if (!(alongX > 0.0 && alongZ > 0.0)) throw std::logic_error("rolling_balls: the return does not fit");
    // The slope blends in over the first straight, which drops by its mean slope there.
    const double start = turtle.slope();
    const double slope = (here.y() - foot.y() - 0.5 * alongX * start) /
                         (0.5 * alongX + kCurve * M_PI + kUTurn * M_PI + alongZ + kFinalRun + kFootRun);
    turtle.run(alongX, 0.0, slope, points);
    turtle.run(kCurve * M_PI / 2, 1.0 / kCurve, slope, points);
    turtle.run(alongZ, 0.0, slope, points);
    turtle.run(kUTurn * M_PI, 1.0 / kUTurn, slope, points);
    turtle.run(kFinalRun, 0.0, slope, points);
    turtle.run(kCurve * M_PI / 2, -1.0 / kCurve, slope, points);
    turtle.run(kFootRun, 0.0, slope, points);
    points.pop_back();  // the lift's first point is the foot itself
    path.liftBegin = points.size();

    // The lift: a half circle up the +x side of the axle. Its cage keeps the same frame all
    // the way (side along the axle, up towards it), so a marble rests in the valley of the two
    // outer wires while gravity presses it outwards and of the inner two beyond the side.
    const int liftSamples = static_cast<int>(std::ceil(M_PI * kLiftRadius / kSampleSpacing));
    for (int i = 0; i < liftSamples; ++i) {
        const double theta = -M_PI / 2 + M_PI * i / liftSamples;
        const Vec3 inward(-std::cos(theta), -std::sin(theta), 0.0);
        points.push_back({kAxle - kLiftRadius * inward, Vec3::UnitZ(), inward});
    }
    path.distance.resize(points.size());
    path.distance[0] = 0.0;
    for (size_t i = 1; i < points.size(); ++i)
        path.distance[i] = path.distance[i - 1] + (points[i].position - points[i - 1].position).norm();
    path.length = path.distance.back() + (points.front().position - points.back().position).norm();
    return path;
}

const SculpturePath& sculpturePath() {
    static const SculpturePath path = buildPath();
    return path;
}

/// One wire of the cage along `line` (open): in corner `corner` up to `flipAt`, in the opposite
/// corner 3 − corner from there on (over the top of the lift the cage's frame comes back turned
/// half a turn about the line: the lift turns the marbles over, the descending track does not),
/// starting at `from`. Corners: 0, 1 the lower wires, 2, 3 the guard wires, seen down the track.
std::shared_ptr<const SplineTube> cageWire(const std::vector<PathPoint>& line, int corner,
                                           size_t flipAt, size_t from = 0) {
    constexpr std::array<double, 4> kSide{-1.0, 1.0, -1.0, 1.0};
    constexpr std::array<double, 4> kUp{-1.0, -1.0, 1.0, 1.0};
    const double offset = kCageRadius / std::sqrt(2.0);
    std::vector<Vec3> points;
    for (size_t i = from; i < line.size(); ++i) {
        const int c = i < flipAt ? corner : 3 - corner;
        points.push_back(line[i].position + offset * (kSide[c] * line[i].side + kUp[c] * line[i].up));
    }
    return makeSplineTube(std::move(points), kWireRadius, false);
}

/// The main cage's line: from the spout's bend round the return, up the lift and down to the
/// drop; and where on it the lift's top is.
std::vector<PathPoint> mainCageLine(const SculpturePath& path, size_t& top) {
    std::vector<PathPoint> line(path.points.begin() + static_cast<long>(path.dropEnd) - 2, path.points.end());
    top = line.size();
    line.insert(line.end(), path.points.begin(), path.points.begin() + static_cast<long>(path.dropBegin) + 1);
    return line;
}

/// Where a marble rests on the lower wires: below the centre line by this much along `up`.
double restingDrop() {
    const double half = kCageRadius / std::sqrt(2.0);
    const double reach = kMarbleRadius + kWireRadius;
    return half - std::sqrt(reach * reach - half * half);
}

/// The gate's bars: the first hinged to the world at the hub, the others welded to it.
void addGate(SceneDescription& scene, const SculpturePath& path) {
    const PathPoint& p = path.points[path.gate];
    const Vec3 along = p.up.cross(p.side);
    const Vec3 hub = p.position - restingDrop() * p.up + kGateHubOffset * p.side;
    Mat3 frame;
    frame << along, p.up, p.side;  // the bars' x along the track, y the hub's axle
    for (int k = 0; k < kGateBars; ++k) {
        const double angle = M_PI * k / kGateBars;
        const std::string name = "gate_" + std::to_string(k);
        scene.bodies.push_back({name,
                                BodyDef{.shape = boxShape(Vec3(2.0 * kGateSpoke, 0.006, 0.004)),
                                        .mass = kGateBarMass,
                                        .position = hub,
                                        .orientation = Quat(frame) * Quat(Eigen::AngleAxisd(angle, Vec3::UnitY())),
                                        .staticFriction = kMarbleFriction,
                                        .dynamicFriction = kMarbleFriction,
                                        .collisionGroup = kArmGroup,
                                        .collisionMask = ~(kWireGroup | kArmGroup)},
                                Vec3(0.25, 0.45, 0.8)});
        if (k == 0) {
            addJoint(scene, "gate_hinge", "", name,
                     JointDef{.type = JointType::Hinge,
                              .anchor0 = hub,
                              .axis0 = p.up,
                              .axis1 = Vec3::UnitY(),
                              .normal0 = along,
                              .normal1 = Vec3::UnitX(),
                              .targetVelocity = -kGateSpeed,  // the spokes cross the track downhill
                              .driveCompliance = kGateCompliance,
                              .angularDamping = kLiftDamping});
            continue;
        }
        addJoint(scene, name + "_weld", "gate_0", name,
                 JointDef{.type = JointType::Fixed,
                          .normal0 = Vec3(std::cos(angle), 0.0, -std::sin(angle)),
                          .normal1 = Vec3::UnitX()});
    }
}

std::string marbleName(int i) {
    char name[16];
    std::snprintf(name, sizeof name, "marble_%02d", i);
    return name;
}

SceneDescription buildRollingBalls() {
    const SculpturePath& path = sculpturePath();
    SceneDescription scene{.name = "rolling_balls", .gravity = kPaperGravity, .substeps = 10};
    scene.bodies.push_back(
        {"base", BodyDef{.shape = planeShape(Vec3::UnitY(), 0.0), .type = BodyType::Static},
         Vec3(0.35, 0.33, 0.3)});
    scene.bodies.push_back({"axle", BodyDef{.shape = cylinderShape(0.03, 0.08),
                                            .type = BodyType::Static,
                                            .position = kAxle,
                                            .orientation = Quat(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitX())),
                                            .collide = false},
                            Vec3(0.3, 0.3, 0.32)});

    // The arms: each turned by its own hinge motor about the axle, all at the same rate, so
    // they keep their spacing without being joined to one another.
    const double armLength = kArmOuter - kArmInner;
    for (int i = 0; i < kArms; ++i) {
        const double angle = 2.0 * M_PI * i / kArms;
        const Vec3 radial(std::cos(angle), std::sin(angle), 0.0);
        const std::string name = "arm_" + std::to_string(i);
        scene.bodies.push_back(
            {name,
             BodyDef{.shape = boxShape(Vec3(armLength, kArmThickness, kArmWidth)),
                     .mass = kArmMass,
                     .position = kAxle + (kArmInner + 0.5 * armLength) * radial,
                     .orientation = Quat(Eigen::AngleAxisd(angle, Vec3::UnitZ())),
                     .staticFriction = kMarbleFriction,
                     .dynamicFriction = kMarbleFriction,
                     .collisionGroup = kArmGroup,
                     .collisionMask = ~kWireGroup},
             Vec3(0.8, 0.55, 0.2)});
        addJoint(scene, "lift_" + std::to_string(i), "", name,
                 JointDef{.type = JointType::Hinge,
                          .anchor0 = kAxle,
                          .anchor1 = Vec3(-kArmInner - 0.5 * armLength, 0.0, 0.0),
                          .axis0 = Vec3::UnitZ(),
                          .axis1 = Vec3::UnitZ(),
                          .normal0 = radial,
                          .normal1 = Vec3::UnitX(),
                          .targetVelocity = kDefaultLiftSpeed,
                          .driveCompliance = kLiftCompliance,
                          .angularDamping = kLiftDamping});
    }

    addGate(scene, path);
    // The wires after the arms and the gate: contact pairs are solved in body order, so a marble an arm
    // presses against a wire is pushed out of the wire last (the sprung arm gives way).
    const auto addWire = [&](const std::string& name, std::shared_ptr<const SplineTube> tube) {
        scene.bodies.push_back({name,
                                BodyDef{.shape = splineShape(std::move(tube)),
                                        .type = BodyType::Static,
                                        .staticFriction = kMarbleFriction,
                                        .dynamicFriction = kMarbleFriction,
                                        .collisionGroup = kWireGroup,
                                        .collisionMask = ~kArmGroup},
                                Vec3(0.75, 0.75, 0.78)});
    };
    size_t top = 0;
    const std::vector<PathPoint> cage = mainCageLine(path, top);
    for (int k = 0; k < 4; ++k) addWire("wire_" + std::to_string(k), cageWire(cage, k, top));
    // The branches: a wide mouth where the marbles land from the switch.
    for (int b = 0; b < 2; ++b)
        for (int k = 0; k < 4; ++k)
            addWire((b == 0 ? "left_" : "right_") + std::to_string(k),
                    k < 2 ? cageWire(path.drop.branches[b], k, path.drop.branches[b].size())
                          : branchGuardWire(path.drop.branches[b], k));
    addWire("exit_pipe", makeSplineTube(path.drop.exitPipe, kPipeRadius, false, true));
    addWire("spout_pipe", makeSplineTube(path.drop.spoutPipe, kPipeRadius, false, true));
    scene.bodies.push_back({"funnel",
                            BodyDef{.shape = triangleMeshShape(funnelMesh(path.drop)),
                                    .type = BodyType::Static,
                                    .staticFriction = kMarbleFriction,
                                    .dynamicFriction = kMarbleFriction},
                            Vec3(0.7, 0.5, 0.25)});
    addSwitch(scene, path.drop);

    // The marbles, spread evenly along the return from the funnel's spout to the foot of the
    // lift, resting on the lower wires: each goes up the lift and through the gate before it
    // reaches the switch (marbles started below the gate would reach it bunched).
    const double returnStart = path.distance[path.dropEnd] + 0.1;
    const double runLength = path.distance[path.liftBegin] - returnStart;
    size_t at = path.dropEnd;
    for (int i = 0; i < kMaxMarbles; ++i) {
        const double s = returnStart + runLength * (i + 0.5) / kMaxMarbles;
        while (at + 1 < path.liftBegin && path.distance[at + 1] <= s) ++at;
        const PathPoint& p = path.points[at];
        scene.bodies.push_back(
            {marbleName(i), BodyDef{.shape = sphereShape(kMarbleRadius),
                                    .density = kGlassDensity,
                                    .position = p.position - restingDrop() * p.up,
                                    .staticFriction = kMarbleFriction,
                                    .dynamicFriction = kMarbleFriction,
                                    .restitution = kMarbleRestitution},
             Vec3(0.1 + 0.8 * ((i * 7) % kMaxMarbles) / kMaxMarbles, 0.35,
                  0.9 - 0.8 * ((i * 5) % kMaxMarbles) / kMaxMarbles)});
    }
    scene.camera =
        SceneCamera{.position = Vec3(1.5, 1.55, 1.75), .target = Vec3(-0.3, 0.8, -0.35), .fov = 0.75};
    return scene;
}

/// Where a marble is along the centre line, found near where it was the frame before.
struct Tracked {
    ecs::Entity id;
    size_t segment = 0;      ///< centre-line segment [segment, segment + 1] it is nearest to
    double offTrack = 0.0;   ///< distance from the centre line (m)
    double progress = 0.0;   ///< unwrapped distance run along the line since the start (m)
    double along = 0.0;      ///< position along the line in [0, length) (m)
    Vec3 velocity = Vec3::Zero();
    double turn = 0.0;       ///< angle its velocity turned by over the last frame (rad)
    /// Between entering the drop and being back in a cage: off the centre line, in a branch or
    /// the funnel, where the nearest segment may be another part of the track passing close by.
    bool inDrop = false;
};

class RollingBallsScript : public SceneScript {
  public:
    std::unique_ptr<SceneScript> clone() const override { return std::make_unique<RollingBallsScript>(*this); }
    RollingBallsScript() {
        marbles_ = addKnob({.name = "marbles",
                            .label = "marbles (more on restart)",
                            .value = kMaxMarbles,
                            .min = 1,
                            .max = kMaxMarbles,
                            .format = "%.0f"});
        liftSpeed_ = addKnob({.name = "lift_speed",
                              .label = "lift speed (rad/s)",
                              .value = kDefaultLiftSpeed,
                              .min = 0.0,
                              .max = 3.0,
                              .format = "%.2f"});
        velocityPass_ = addKnob({.name = "velocity_pass",
                                 .label = "velocity pass (off: plain PBD)",
                                 .kind = SceneKnob::Kind::Toggle,
                                 .value = 1.0});
        std::vector<std::string> follow{"the whole sculpture"};
        for (int i = 0; i < kMaxMarbles; ++i) follow.push_back(marbleName(i));
        follow_ = addKnob({.name = "follow",
                           .label = "camera",
                           .kind = SceneKnob::Kind::Choice,
                           .choices = std::move(follow)});
    }

    void start(SceneInstance& scene) override {
        tracked_.clear();
        for (int i = 0; i < kMaxMarbles; ++i) {
            const ecs::Entity id = scene.bodyNamed(marbleName(i));
            if (scene.registry.isValid(id)) tracked_.push_back({.id = id});
        }
        lifts_.clear();
        for (int i = 0; i < kArms; ++i) lifts_.push_back(scene.jointNamed("lift_" + std::to_string(i)));
        applyKnobs(scene);
        // Place each marble on the line by a search over all of it, once.
        const SculpturePath& path = sculpturePath();
        for (Tracked& marble : tracked_) {
            marble.segment = nearestSegment(path, motion(scene, marble).centreOfMass, 0, path.points.size());
            observe(scene, marble, true);
        }
        fastestTurn_ = 0.0;
        recordTurn_ = 0.0;
    }

    void knobChanged(SceneInstance& scene, size_t /*index*/) override { applyKnobs(scene); }

    void beforeFrame(SceneInstance& scene, double /*time*/, double /*dt*/) override {
        // The state the last frame left (the first call sees the start).
        fastestSpeed_ = 0.0;
        fastestTurn_ = 0.0;
        for (Tracked& marble : tracked_) {
            if (!scene.registry.isValid(marble.id)) continue;
            observe(scene, marble, false);
            const double speed = marble.velocity.norm();
            if (speed > fastestSpeed_) fastestSpeed_ = speed;
        }
        // The fastest marble in the spring, and how far its path turned over the last frame.
        const SculpturePath& path = sculpturePath();
        double fastestInSpring = -1.0;
        for (const Tracked& marble : tracked_) {
            if (!scene.registry.isValid(marble.id) || marble.segment < path.springBegin ||
                marble.segment >= path.springEnd)
                continue;
            const double speed = marble.velocity.norm();
            if (speed > fastestInSpring) {
                fastestInSpring = speed;
                fastestTurn_ = marble.turn;
            }
        }
        recordTurn_ = std::max(recordTurn_, fastestTurn_);
    }

    void readouts(const SceneInstance& scene, std::vector<SceneReadout>& out) const override {
        const SculpturePath& path = sculpturePath();
        int laps = 0;
        int onTrack = 0;
        for (const Tracked& marble : tracked_) {
            if (!scene.registry.isValid(marble.id)) continue;
            laps += static_cast<int>(std::floor(marble.progress / path.length));
            // In the drop the marbles leave the centre line for a branch: the whole of it counts.
            onTrack += marble.offTrack < (marble.inDrop ? kDropReach : kCageRadius);
        }
        constexpr double kDegree = M_PI / 180.0;
        out.push_back({"laps completed", static_cast<double>(laps), "%.0f"});
        out.push_back({"marbles on the track", static_cast<double>(onTrack), "%.0f"});
        out.push_back({"fastest marble (m/s)", fastestSpeed_, "%.2f"});
        out.push_back({"turn per frame in the spring (deg)", fastestTurn_ / kDegree, "%.0f"});
        out.push_back({"largest turn per frame so far (deg)", recordTurn_ / kDegree, "%.0f"});
    }

    std::optional<SceneCamera> camera(const SceneInstance& scene) const override {
        const size_t followed = static_cast<size_t>(knob(follow_));
        if (followed == 0 || followed > tracked_.size()) return std::nullopt;
        const Tracked& marble = tracked_[followed - 1];
        if (!scene.registry.isValid(marble.id)) return std::nullopt;
        // From behind and above the marble, looking along the track.
        const SculpturePath& path = sculpturePath();
        const PathPoint& p = path.points[marble.segment];
        const Vec3 ahead = (path.points[(marble.segment + 1) % path.points.size()].position -
                            p.position).normalized();
        const Vec3& x = motion(scene, marble).centreOfMass;
        return SceneCamera{.position = x - 0.25 * ahead + 0.12 * Vec3::UnitY(), .target = x, .fov = 1.0};
    }

  private:
    /// A marble's motion as the physics system wrote it after the last step.
    static const ecs::RigidBody& motion(const SceneInstance& scene, const Tracked& marble) {
        return scene.registry.get<ecs::RigidBody>(marble.id);
    }

    /// Where the knobs act, through the engine layer: solver settings, the lift's motors, the
    /// marble count.
    void applyKnobs(SceneInstance& scene) {
        ecs::PhysicsSystem physics = scene.physics();
        WorldSettings settings = physics.settings();
        settings.velocityPass = toggled(velocityPass_);
        physics.setSettings(settings);
        for (const ecs::Entity lift : lifts_) {
            if (!scene.registry.isValid(lift)) continue;
            scene.registry.patch<ecs::Joint>(lift, [&](ecs::Joint& motor) { motor.def.targetVelocity = knob(liftSpeed_); });
        }
        // Fewer marbles: the last ones are taken out of the sculpture.
        const size_t count = static_cast<size_t>(knob(marbles_));
        for (size_t i = count; i < tracked_.size(); ++i) physics.destroy(tracked_[i].id);
        if (count < tracked_.size()) tracked_.resize(count);
    }

    /// Reads one marble: its place along the centre line (searched from a little behind where
    /// it was to as far ahead as it can run in a frame), velocity and turn.
    void observe(const SceneInstance& scene, Tracked& marble, bool first) const {
        const SculpturePath& path = sculpturePath();
        const ecs::RigidBody& body = motion(scene, marble);
        const size_t n = path.points.size();
        if (!first) {
            constexpr size_t kBehind = 5;
            constexpr size_t kAhead = 40;  // 0.8 m of line: 48 m/s at 60 frames per second
            marble.segment = nearestSegment(path, body.centreOfMass, marble.segment + n - kBehind, kBehind + kAhead);
        }
        const Vec3& a = path.points[marble.segment].position;
        const Vec3& b = path.points[(marble.segment + 1) % n].position;
        const Vec3 ab = b - a;
        const double u = std::clamp((body.centreOfMass - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
        marble.offTrack = (body.centreOfMass - (a + u * ab)).norm();
        if (marble.segment >= path.dropBegin && marble.segment < path.dropEnd)
            marble.inDrop = true;
        else if (marble.offTrack < kCageRadius)
            marble.inDrop = false;
        const double along = path.distance[marble.segment] + u * ab.norm();
        if (!first) {
            double step = along - marble.along;
            if (step > 0.5 * path.length) step -= path.length;
            if (step < -0.5 * path.length) step += path.length;
            marble.progress += step;
            const double cross = marble.velocity.cross(body.velocity).norm();
            marble.turn = std::atan2(cross, marble.velocity.dot(body.velocity));
        }
        marble.along = along;
        marble.velocity = body.velocity;
    }

    /// The segment of the closed centre line nearest to x among `count` from `first` (mod n).
    static size_t nearestSegment(const SculpturePath& path, const Vec3& x, size_t first, size_t count) {
        const size_t n = path.points.size();
        size_t best = first % n;
        double bestDistance2 = std::numeric_limits<double>::infinity();
        for (size_t k = 0; k < count; ++k) {
            const size_t i = (first + k) % n;
            const Vec3& a = path.points[i].position;
            const Vec3 ab = path.points[(i + 1) % n].position - a;
            const double u = std::clamp((x - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
            const double d2 = (x - a - u * ab).squaredNorm();
            if (d2 < bestDistance2) {
                bestDistance2 = d2;
                best = i;
            }
        }
        return best;
    }

    size_t marbles_ = 0;
    size_t liftSpeed_ = 0;
    size_t velocityPass_ = 0;
    size_t follow_ = 0;
    std::vector<Tracked> tracked_;
    std::vector<ecs::Entity> lifts_;
    double fastestSpeed_ = 0.0;
    double fastestTurn_ = 0.0;  ///< rad, of the fastest marble in the spring, last frame
    double recordTurn_ = 0.0;   ///< rad, the largest of those so far
};

}  // namespace

SceneEntry rollingBallsEntry() {
    return {.name = "rolling_balls",
            .description = "Figs. 1, 14: marbles circulating on a wire sculpture: a spring, a see-saw switch, a funnel, a paddle-wheel lift",
            .build = buildRollingBalls,
            .paperMsPerFrame = 15,
            .makeScript = []() -> std::unique_ptr<SceneScript> {
                return std::make_unique<RollingBallsScript>();
            }};
}

}  // namespace substep::scenes
