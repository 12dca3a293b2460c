#pragma once
/// A direct (block) solve of the joints around light bodies, instead of projecting them one
/// after another.
///
/// Why: Gauss-Seidel passes on only about m_light/(m_light + m_heavy) of a correction through a
/// light body held between two constraints (the correction of one joint moves mostly the light
/// body, which the next joint then pulls back), so a light link acts as a spring of stiffness
/// about m_light/(4 h²): a 1 g box holding a 1 kg box on hard joints opened its top joint by
/// 6.8 mm at rest with 20 substeps, and a 0.1 g servo arm could not turn 20 g knuckles.
///
/// What: a dynamic body is light when a dynamic body it is jointed to is at least
/// kLightMassRatio times heavier (a static neighbour does not count: a body hung from the world
/// alone is projected exactly, and counting it would cluster the top of every chain). The joints
/// touching a light body form a cluster; clusters that share a joint merge, and a joint between
/// two dynamic bodies of one cluster joins it (a linkage's heavy body keeps its own hinge, or
/// the cluster would drag it off that hinge by f h²/m every substep). A light body on a single
/// joint is projected exactly already and forms no cluster. Clusters are found by union-find
/// over the joint graph, only when joints are created or destroyed. Each substep, each
/// cluster's joint parts are linearised into rows (joints/joint_rows.h) and solved together:
///
///     (J W Jᵀ + α̃) Δλ = c − α̃ λ        (Eq. 4 for every row at once, α̃ = α/h²)
///
/// with W the bodies' inverse masses and world inverse inertias (the ingredients of Eqs. 2-3 and
/// Eqs. 11-12), by Eigen's LDLT on the Jacobi-scaled matrix in fixed-size storage. The bodies move
/// by the paper's update (Eqs. 6-9, Eqs. 15-16) for the summed Δλ, and each part's λ and impulse
/// are updated, so the force and torque readouts (Eq. 10, Eq. 17) and the velocity pass work as
/// for projected joints.
///
/// Inequalities (limits, ropes) enter when violated or within kLimitMargin of their bound; a
/// row whose λ would pull is dropped and the system solved again (an active-set loop of at most
/// as many passes as there are rows).
///
/// The rest of the world is unchanged: joints outside clusters are projected as before, each
/// cluster in the place of its first joint in the joint order, contacts after them. A world with
/// no light body gives the same bytes as without the block solve. Off under the Jacobi solver,
/// in the repair pass and with WorldSettings::blockSolve = false; a cluster of more than
/// kMaxBlockRows rows stays with Gauss-Seidel. Not caught: a link light only against a load one
/// joint further on (the criterion is on the neighbours' masses, not on the effective inverse
/// mass at the anchor).

#include "physics/body.h"
#include "physics/correction.h"
#include "physics/joints/joint.h"

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace substep {

/// A dynamic body jointed to a dynamic body at least this many times heavier is light.
inline constexpr double kLightMassRatio = 20.0;

/// The clusters and their scratch storage (allocated when the clusters are built, reused by
/// every solve).
class JointBlockSolver {
public:
    JointBlockSolver();
    ~JointBlockSolver();
    JointBlockSolver(JointBlockSolver&&) noexcept;
    JointBlockSolver& operator=(JointBlockSolver&&) noexcept;

    /// Finds the clusters of the live joints. Call when joints are created or destroyed.
    void build(std::span<const Body> bodies, std::span<const Joint> joints);
    /// Whether there is any cluster.
    bool empty() const { return clusters_.empty(); }
    /// Number of clusters.
    size_t clusterCount() const { return clusters_.size(); }
    /// Whether joint `index` is solved in a cluster (its Gauss-Seidel projection is skipped).
    bool clustered(uint32_t index) const { return index < clusterOf_.size() && clusterOf_[index] != kNoCluster; }
    /// Whether clustered joint `index` is its cluster's first, where solveAt solves the cluster.
    bool leadsCluster(uint32_t index) const {
        return clusterJoints_[clusters_[clusterOf_[index]].firstJoint] == index;
    }
    /// In the world's pass over the joints, at clustered joint `index`: one block solve of its
    /// cluster when it is the cluster's first joint, so that a cluster takes the place of its
    /// first joint in the Gauss-Seidel order; nothing at its other joints.
    void solveAt(SolverContext& ctx, std::span<Joint> joints, uint32_t index) {
        if (leadsCluster(index)) solveCluster(ctx, joints, clusters_[clusterOf_[index]]);
    }

private:
    struct Cluster {
        uint32_t firstJoint = 0;  ///< into clusterJoints_
        uint32_t jointCount = 0;
        uint32_t firstBody = 0;   ///< into clusterBodies_: the dynamic bodies its joints move
        uint32_t bodyCount = 0;
    };
    struct Scratch;
    void solveCluster(SolverContext& ctx, std::span<Joint> joints, const Cluster& cluster);

    std::vector<Cluster> clusters_;
    std::vector<uint32_t> clusterJoints_;  ///< joint indices, cluster by cluster, ascending
    std::vector<uint32_t> clusterBodies_;  ///< body indices, cluster by cluster
    static constexpr uint32_t kNoCluster = ~0u;
    std::vector<uint32_t> clusterOf_;      ///< per joint: its cluster, or kNoCluster
    std::unique_ptr<Scratch> scratch_;
};

}  // namespace substep
