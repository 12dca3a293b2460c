#pragma once
/// The substep corrections as the viewer shows them (issue 20): after a substep stepped by hand,
/// what each joint and contact pair moved each of its bodies, named ("hinge 'h2' moved 'box3'
/// 0.42 mm"), sorted by size for the panel, and drawn as arrows at the bodies' centres (the
/// displacement in lime, the rotation vector in white), scaled so the largest is about twice
/// its body's size. Reads the world's record (physics/substep_corrections.h) and the components'
/// names; knows nothing of ImGui.

#include "physics/substep_corrections.h"
#include "physics/world.h"
#include "render/render_scene.h"
#include "scene/scene.h"

#include <optional>
#include <string>
#include <vector>

namespace substep::view {

/// One body's share of one constraint's correction.
struct CorrectionEntry {
    std::string constraint;  ///< "hinge 'h2'", "contact 'box3' / 'ground'"
    std::string body;        ///< "'box3'"
    ConstraintKind kind = ConstraintKind::Joint;
    uint32_t bodyIndex = 0;            ///< in World::bodies()
    Vec3 displacement = Vec3::Zero();  ///< of the centre of mass (m)
    Vec3 rotation = Vec3::Zero();      ///< rotation vector (rad)
    /// The size it is sorted by: the largest motion of a point of the body, |Δx| + |Δθ| reach (m).
    double size = 0.0;
    /// "hinge 'h2' moved 'box3' 0.42 mm, turned it 0.031°".
    std::string describe() const;
};

/// One body's share of one constraint's velocity change in the substep's velocity pass
/// (Eqs. 29-35: joint damping, restitution, dynamic friction).
struct VelocityEntry {
    std::string constraint;  ///< "contact 'ball' / 'ground'", "hinge 'h2'"
    std::string body;
    ConstraintKind kind = ConstraintKind::Contact;
    uint32_t bodyIndex = 0;
    Vec3 velocity = Vec3::Zero();         ///< change of the centre's velocity (m/s)
    Vec3 angularVelocity = Vec3::Zero();  ///< change of the angular velocity (rad/s)
    /// A contact pair's change split along its normal (restitution and the normal velocity,
    /// Eq. 34) and across it (dynamic friction, Eq. 30); nullopt for other constraints.
    std::optional<double> normal;
    std::optional<double> tangential;
    /// The size it is sorted by: |Δv| + |Δω| reach (m/s).
    double size = 0.0;
    /// "contact 'ball' / 'ground' changed 'ball' by 2.1 m/s (normal +2.0, friction 0.6), 3.4 rad/s".
    std::string describe() const;
};

/// One soft body's share of one soft stage (substep_corrections.h's SoftStage): what it moved
/// (or for the velocity pass, changed) of the soft body's particles.
struct SoftStageEntry {
    std::string softBody;  ///< "'tyre_fl'"
    SoftStage stage = SoftStage::Elements;
    std::size_t first = 0;  ///< its particles in SubstepCorrections::particleCorrections
    std::size_t count = 0;
    int moved = 0;          ///< particles it moved
    double largest = 0.0;   ///< the largest particle's motion (m; m/s for the velocity pass)
    /// "soft elements of 'tyre_fl' moved 412 particles, up to 0.31 mm".
    std::string describe() const;
};

/// Every dynamic body's share of the last recorded substep's corrections, largest first (none
/// while the world records nothing, and none that moved nothing).
std::vector<CorrectionEntry> listCorrections(SceneInstance& scene);
/// Every dynamic body's share of the last recorded substep's velocity pass, largest first.
std::vector<VelocityEntry> listVelocityChanges(SceneInstance& scene);
/// Each soft body's share of each soft stage of the last recorded substep that moved one of its
/// particles, in stage order.
std::vector<SoftStageEntry> listSoftCorrections(SceneInstance& scene);

/// Arrows for `entries` at their bodies' centres (as the world has them now) into `lines`.
void drawCorrections(const std::vector<CorrectionEntry>& entries, const World& world,
                     std::vector<render::DebugLine>& lines);
/// Arrows for the velocity changes at their bodies' centres (pink), on a scale of their own:
/// the largest drawn about twice its body's size.
void drawVelocityChanges(const std::vector<VelocityEntry>& entries, const World& world,
                         std::vector<render::DebugLine>& lines);
/// An arrow at each particle a soft stage moved, in the stage's colour (softStageColour), each
/// stage scaled so its largest is a tenth of its soft body's extent.
void drawSoftCorrections(const std::vector<SoftStageEntry>& entries, const World& world,
                         std::vector<render::DebugLine>& lines);
/// The colour a soft stage's particle arrows are drawn in.
render::Colour softStageColour(SoftStage stage);

/// "0.42 mm", "3.1 µm", "1.2 m": a length with a readable unit.
std::string formatLength(double metres);

}  // namespace substep::view
