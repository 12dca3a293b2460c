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

/// Every dynamic body's share of the last recorded substep's corrections, largest first (none
/// while the world records nothing, and none that moved nothing).
std::vector<CorrectionEntry> listCorrections(SceneInstance& scene);

/// Arrows for `entries` at their bodies' centres (as the world has them now) into `lines`.
void drawCorrections(const std::vector<CorrectionEntry>& entries, const World& world,
                     std::vector<render::DebugLine>& lines);

/// "0.42 mm", "3.1 µm", "1.2 m": a length with a readable unit.
std::string formatLength(double metres);

}  // namespace substep::view
