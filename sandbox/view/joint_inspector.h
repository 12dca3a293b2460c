#pragma once
/// The joint inspector: which joint a click near one of its anchors selects (or the panel's
/// list), and what the panel shows of it: name, type, its bodies, force (Eq. 10) and torque
/// (Eq. 17) of the last substep, positional and angular error, its coordinate within its limits,
/// the drive's target and how near the joint is to it. Forces and errors come from the joint's
/// component (the physics system writes them back); anchors and frames from the world's
/// read-only view. The selected joint is highlighted in the view.

#include "view/body_dragger.h"

#include "render/render_scene.h"
#include "scene/scene.h"

#include <optional>
#include <string>
#include <vector>

namespace substep::view {

/// What the inspector shows of a joint.
struct JointDetails {
    std::string name;   ///< its Name, or "joint N" by entity index
    std::string type;   ///< "hinge", "distance", "fixed", "spherical", "prismatic"
    std::string body0;  ///< its bodies' names; "the world" for none
    std::string body1;
    double force = 0.0;   ///< N, Eq. 10: |Σ impulses| / h² of the last substep
    double torque = 0.0;  ///< N m, Eq. 17
    double error = 0.0;   ///< m, the anchors' gap (a rope's excess length)
    double angleError =
        0.0;  ///< rad: a hinge's axes apart, a weld's or slider's turn, a cone's excess
    /// The joint's coordinate: a hinge's angle (rad), a prismatic joint's offset (m), a ball
    /// joint's swing (rad); `angular` says which unit.
    double coordinate = 0.0;
    bool angular = true;
    bool hasCoordinate = false;   ///< distance and fixed joints have none
    std::optional<Range> limits;  ///< in the coordinate's unit (a ball joint: [0, swing limit])
    bool hasDrive = false;
    double target = 0.0;          ///< the drive's current target (a motor's advancing angle)
    double reach = 0.0;           ///< coordinate − target, wrapped to (−π, π] for angles
    Vec3 anchor0 = Vec3::Zero();  ///< world anchors now
    Vec3 anchor1 = Vec3::Zero();
    /// Where the coordinate lies in its limits, 0 at the lower and 1 at the upper (outside
    /// [0, 1] beyond them); nullopt without limits.
    std::optional<double> withinLimits() const;
};

/// The joint with an anchor nearest `ray` within `pixels` screen pixels, each pixel being
/// `radiansPerPixel` of the view (its vertical field of view / its height in pixels); nullopt
/// when none is that near.
std::optional<ecs::Entity> pickJoint(SceneInstance& scene, const Ray& ray, double radiansPerPixel,
                                     double pixels = 12.0);

/// The inspection of joint `entity`; nullopt when it is no live joint (a restart, a load).
std::optional<JointDetails> inspectJoint(SceneInstance& scene, ecs::Entity entity);

/// The selected joint's highlight: a cross at each anchor and lines from them to their bodies'
/// centres, in `colour`.
void highlightJoint(SceneInstance& scene, ecs::Entity entity, const render::Colour& colour,
                    std::vector<render::DebugLine>& lines);

}  // namespace substep::view
