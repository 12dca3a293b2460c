#pragma once
// The rolling ball sculpture's parts shared by rolling_balls.cpp (the circuit, the lift, the
// script) and rolling_balls_drop.cpp (the drop: the see-saw switch, its branches, the funnel).

#include "scenes/scenes.h"

#include "physics/collision/shape.h"
#include "physics/collision/spline_tube.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <vector>

namespace substep::scenes::rolling_balls {

// Marbles: 25 mm glass, the size of Morrell's.
inline constexpr double kMarbleRadius = 0.0125;  ///< m
inline constexpr double kGlassDensity = 2500;    ///< kg/m³
inline constexpr int kMaxMarbles = 24;
inline constexpr double kMarbleFriction = 0.05;
inline constexpr double kMarbleRestitution = 0.3;

// Wires: each at kCageRadius from the centre line, at ±45° from the track's down direction.
inline constexpr double kWireRadius = 0.0015;  ///< m
/// 1.5 mm of play: a marble touches the two lower wires and clears the guard wires by 3 mm,
/// while the gap between two neighbouring wires (2 x 11 mm - 3 mm) stays below its diameter.
inline constexpr double kCageRadius = kMarbleRadius + kWireRadius + 0.0015;
inline constexpr double kSampleSpacing = 0.02;  ///< m of centre line between control points

/// Collision filter groups: the lift's arms sweep through the wire cage between the wires and
/// meet only the marbles (the wires and the arms would otherwise jam the wheel).
inline constexpr uint32_t kArmGroup = 2;
inline constexpr uint32_t kWireGroup = 4;
/// A point of the centre line with the cage's cross-section frame there.
struct PathPoint {
    Vec3 position;
    Vec3 side;  ///< unit, normal to the line; the wires sit at ±45° between side and up
    Vec3 up;    ///< unit, normal to the line and to side: away from the lower wires
};

/// Draws the descending part of the track like a turtle: a heading in the horizontal plane,
/// turning at a curvature, and a slope (drop per horizontal metre) blended between pieces.
class Turtle {
  public:
    Turtle(const Vec3& start, double heading, double slope = 0.0)
        : position_(start), heading_(heading), slope_(slope) {}

    /// `length` horizontal metres turning at `curvature` (1/m, positive to the left seen from
    /// above), the slope blending smoothly from the current one to `slopeEnd`.
    void run(double length, double curvature, double slopeEnd, std::vector<PathPoint>& out) {
        advance(length, curvature, curvature, slopeEnd, out);
    }

    /// The same with the curvature changing evenly from the current one to `curvatureEnd` (a
    /// clothoid: a marble entering the spring is pressed outwards gradually, not at once).
    void ease(double length, double curvatureEnd, double slopeEnd, std::vector<PathPoint>& out) {
        advance(length, curvature_, curvatureEnd, slopeEnd, out);
    }

    const Vec3& position() const { return position_; }
    double heading() const { return heading_; }
    double slope() const { return slope_; }
    Vec3 direction() const {
        return Vec3(std::cos(heading_), -slope_, -std::sin(heading_)).normalized();
    }

    /// The cage frame of a descending track: side horizontal, up as near the vertical as the
    /// slope allows.
    static PathPoint framed(const Vec3& position, const Vec3& tangent) {
        const Vec3 side = tangent.cross(Vec3::UnitY()).normalized();
        return {position, side, side.cross(tangent).normalized()};
    }

  private:
    void advance(double length, double curvatureStart, double curvatureEnd, double slopeEnd,
                 std::vector<PathPoint>& out) {
        // A control point every kSampleSpacing, and at least every 15° of turn (the spring).
        const double turn = std::max(std::abs(curvatureStart), std::abs(curvatureEnd)) * length;
        const int steps = std::max(
            {1, static_cast<int>(std::ceil(length / kSampleSpacing)),
             static_cast<int>(std::ceil(turn / (M_PI / 12)))});
        const double slopeStart = slope_;
        constexpr int kSubsteps = 16;  // integration steps per control point
        const double dl = length / (steps * kSubsteps);
        for (int i = 1; i <= steps; ++i) {
            for (int k = 1; k <= kSubsteps; ++k) {
                const double u = (static_cast<double>(i - 1) + (k - 0.5) / kSubsteps) / steps;
                const double blend = u * u * (3.0 - 2.0 * u);
                slope_ = slopeStart + (slopeEnd - slopeStart) * blend;
                const double curvature = curvatureStart + (curvatureEnd - curvatureStart) * u;
                heading_ += 0.5 * curvature * dl;
                position_ += dl * Vec3(std::cos(heading_), -slope_, -std::sin(heading_));
                heading_ += 0.5 * curvature * dl;
            }
            out.push_back(framed(position_, direction()));
        }
        slope_ = slopeEnd;
        curvature_ = curvatureEnd;
    }

    Vec3 position_;
    double heading_;  ///< rad: direction (cos, 0, −sin), so 0 is +x and π/2 is −z
    double slope_;
    double curvature_ = 0.0;  ///< 1/m, where the last piece ended
};

// The drop, the switch and the funnel (constants in m, angles in rad).
inline constexpr double kPipeRadius = kMarbleRadius + 0.00225;  ///< a marble in it sits as on the wires
inline constexpr double kExitBend = 0.04;     ///< radius of the pipe turning the marbles down
inline constexpr double kPipeDown = 0.02;     ///< straight down at the end of that pipe
inline constexpr double kPivotBelowExit = 0.05;
inline constexpr double kBeamHalf = 0.055;    ///< the see-saw's half length, across the track
inline constexpr double kBeamThickness = 0.006;
inline constexpr double kPartWidth = 0.032;   ///< of the beam and the fin, along the track
inline constexpr double kFinHeight = 0.035;   ///< above the beam
inline constexpr double kFinThickness = 0.004;
inline constexpr double kLipHeight = 0.008;
inline constexpr double kWallHalf = 0.3;     ///< the walls' half length across the track: to the catches' ends
inline constexpr double kWallHeight = 0.12;
inline constexpr double kLipThickness = 0.003;
inline constexpr double kSwitchTilt = 20.0 * M_PI / 180.0;  ///< the hinge's limits, either way
inline constexpr double kSwitchDamping = 5.0;  ///< 1/s: the beam settles against its limit, not bounce back
inline constexpr double kBranchDrop = 0.04;   ///< branch start below the pivot
inline constexpr double kBranchSlope = 0.15;
/// The branches' first straight, open above where the marbles land from the switch.
inline constexpr double kBranchCatch = 0.24;
inline constexpr size_t kBranchGuardFrom = 12;  ///< control points: the guard wires close in over 24 cm
inline constexpr double kBranchMouth = 0.028;  ///< half width of the catch's mouth
inline constexpr double kBranchBend = 0.08;   ///< radius of the branches' quarter turns
inline constexpr double kBranchStraight = 0.05;
inline constexpr double kFunnelRim = 0.06;    ///< radius of the funnel's rim
/// Radius of its hole: the spout pipe's, so a marble passes from the cone into the pipe without a step.
inline constexpr double kFunnelHole = kPipeRadius;
inline constexpr double kFunnelSteepness = 1.73;  ///< height per radius of the cone: 60°
inline constexpr double kRimBelowBranch = 0.03;   ///< the rim below the branches' ends
inline constexpr double kSpoutDown = 0.02;
inline constexpr double kSpoutBend = 0.06;
inline constexpr double kReturnSlope = 0.1;   ///< where the spout hands over to the cage
/// How far from the drop's centre line its parts reach (the branches, the funnel): the
/// branches' outer bends run 0.38 m out across the track and below the line.
inline constexpr double kDropReach = 0.45;

/// Where the drop's parts are, from the end of the cage (`cageEnd`, heading `heading`).
struct DropLayout {
    Vec3 along = Vec3::UnitX();  ///< horizontal, the track's direction at the cage's end
    Vec3 across = Vec3::UnitZ(); ///< horizontal, = up x along: the switch's "right"
    double heading = 0.0;
    std::vector<Vec3> exitPipe;  ///< centre line of the pipe from the cage down to the switch
    Vec3 pivot = Vec3::Zero();
    std::array<std::vector<PathPoint>, 2> branches;  ///< left (−across), right (+across)
    Vec3 hole = Vec3::Zero();    ///< centre of the funnel's hole
    std::vector<Vec3> spoutPipe; ///< from the hole into the return's cage
};

/// A framed point of a line that may run vertically: the frame's side is `across`.
PathPoint framedAcross(const Vec3& position, const Vec3& tangent, const Vec3& across);

/// Lays the drop out from the end of the cage (`cageEnd`, heading `heading` as the Turtle's).
DropLayout layDrop(const Vec3& cageEnd, double heading);

/// The funnel: a cone of triangles from the rim down to the hole, facing in and up.
std::shared_ptr<const TriangleMesh> funnelMesh(const DropLayout& d);

/// Adds the switch's bodies and joints (see rolling_balls_drop.cpp).
void addSwitch(SceneDescription& scene, const DropLayout& d);

/// A guard wire of a branch (corner 2 or 3): over the catch it starts low and wide and closes
/// in to its corner, a mouth that turns a marble landing off the middle onto the lower wires.
std::shared_ptr<const SplineTube> branchGuardWire(const std::vector<PathPoint>& line, int corner);

}  // namespace substep::scenes::rolling_balls
