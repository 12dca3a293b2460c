#include "physics/joint_block_solve.h"

#include "physics/joints/joint_rows.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

namespace substep {
namespace {

using BlockMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxBlockRows, kMaxBlockRows>;
using BlockVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxBlockRows, 1>;

/// Added to the unit diagonal of the scaled system: keeps redundant rows (a closed loop) from
/// making LDLT divide by a zero pivot. As a compliance it is 1e-10 of each row's own inverse
/// mass, far below anything a joint can show.
constexpr double kRegularisation = 1e-10;

/// A body's inverse mass and world inverse inertia, and the motion the solve gives it.
struct BodyWeights {
    uint32_t index = 0;
    double invMass = 0.0;
    Mat3 invInertia = Mat3::Zero();
    Vec3 dx = Vec3::Zero();
    Vec3 dtheta = Vec3::Zero();
};

/// One side of a row: which body (local index, −1: none that moves) and its Jacobian, the
/// linear and angular impulse per unit λ (Eqs. 2-3 and Eqs. 11-12 are Jᵀ W J of one side).
struct RowSide {
    int body = -1;
    Vec3 linear = Vec3::Zero();
    Vec3 angular = Vec3::Zero();
    Vec3 weightedAngular = Vec3::Zero();  ///< I⁻¹ angular
};

int findBody(const BodyWeights* weights, int count, uint32_t index) {
    for (int i = 0; i < count; ++i)
        if (weights[i].index == index) return i;
    return -1;
}

/// Union-find root with path halving.
uint32_t root(std::vector<uint32_t>& parent, uint32_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
}

}  // namespace

struct JointBlockSolver::Scratch {
    JointRows rows;
    std::array<std::array<RowSide, 2>, kMaxBlockRows> sides;
    std::array<double, kMaxBlockRows> lambda{};
    std::array<bool, kMaxBlockRows> active{};
    std::vector<BodyWeights> bodies;  ///< sized to the largest cluster when built
    BlockMatrix a;
    BlockMatrix scaled;
    BlockVector rhs;
    BlockVector scale;
    BlockVector step;
    Eigen::LDLT<BlockMatrix> ldlt;
};

JointBlockSolver::JointBlockSolver() = default;
JointBlockSolver::~JointBlockSolver() = default;
JointBlockSolver::JointBlockSolver(JointBlockSolver&&) noexcept = default;
JointBlockSolver& JointBlockSolver::operator=(JointBlockSolver&&) noexcept = default;

void JointBlockSolver::build(std::span<const Body> bodies, std::span<const Joint> joints) {
    clusters_.clear();
    clusterJoints_.clear();
    clusterBodies_.clear();
    clusterOf_.assign(joints.size(), kNoCluster);
    // Light bodies: jointed to a dynamic body at least kLightMassRatio times heavier.
    std::vector<uint8_t> light(bodies.size(), 0);
    bool any = false;
    for (const Joint& joint : joints) {
        if (!joint.alive || joint.body0 == joint.body1) continue;
        const Body& b0 = bodies[joint.body0];
        const Body& b1 = bodies[joint.body1];
        if (!b0.isDynamic() || !b1.isDynamic()) continue;
        if (b0.mass * kLightMassRatio <= b1.mass) light[joint.body0] = 1, any = true;
        if (b1.mass * kLightMassRatio <= b0.mass) light[joint.body1] = 1, any = true;
    }
    if (!any) {
        clusterOf_.clear();
        return;
    }
    // The joints of each light body join one set; sets sharing a joint merge.
    constexpr uint32_t kNone = ~0u;
    std::vector<uint32_t> parent(joints.size());
    std::iota(parent.begin(), parent.end(), 0u);
    std::vector<uint32_t> firstJoint(bodies.size(), kNone);
    std::vector<uint8_t> member(joints.size(), 0);
    for (uint32_t j = 0; j < joints.size(); ++j) {
        const Joint& joint = joints[j];
        if (!joint.alive || joint.body0 == joint.body1) continue;
        for (const uint32_t b : {joint.body0, joint.body1}) {
            if (!light[b]) continue;
            member[j] = 1;
            if (firstJoint[b] == kNone) firstJoint[b] = j;
            else parent[root(parent, j)] = root(parent, firstJoint[b]);
        }
    }
    // A joint between two dynamic bodies of one set closes a loop through it (the heavy body's
    // own hinge in a linkage): it joins, or the set would drag the body off it every substep.
    std::vector<uint32_t> setOf(bodies.size(), kNone);  // a body's set, kNone: none or several
    std::vector<uint8_t> shared(bodies.size(), 0);
    for (uint32_t j = 0; j < joints.size(); ++j) {
        if (!member[j]) continue;
        for (const uint32_t b : {joints[j].body0, joints[j].body1}) {
            const uint32_t set = root(parent, j);
            if (setOf[b] == kNone) setOf[b] = set;
            else if (root(parent, setOf[b]) != set) shared[b] = 1;
        }
    }
    for (uint32_t j = 0; j < joints.size(); ++j) {
        const Joint& joint = joints[j];
        if (member[j] || !joint.alive || joint.body0 == joint.body1) continue;
        const uint32_t b0 = joint.body0, b1 = joint.body1;
        if (!bodies[b0].isDynamic() || !bodies[b1].isDynamic() || shared[b0] || shared[b1]) continue;
        if (setOf[b0] == kNone || setOf[b1] == kNone || root(parent, setOf[b0]) != root(parent, setOf[b1])) continue;
        member[j] = 1;
        parent[j] = root(parent, setOf[b0]);
    }
    // Gather each set's joints in ascending order, sets by their first joint.
    std::vector<uint32_t> order;
    for (uint32_t j = 0; j < joints.size(); ++j)
        if (member[j]) order.push_back(j);
    std::stable_sort(order.begin(), order.end(),
                     [&](uint32_t a, uint32_t b) { return root(parent, a) < root(parent, b); });
    size_t largestBodies = 0;
    for (size_t begin = 0; begin < order.size();) {
        size_t end = begin + 1;
        while (end < order.size() && root(parent, order[end]) == root(parent, order[begin])) ++end;
        int rows = 0;
        for (size_t i = begin; i < end; ++i) rows += maxJointRows(joints[order[i]]);
        // A light body on a single joint is projected exactly already; a cluster too large for
        // the fixed storage stays with Gauss-Seidel.
        if (end - begin >= 2 && rows <= kMaxBlockRows) {
            Cluster cluster{.firstJoint = static_cast<uint32_t>(clusterJoints_.size()),
                            .jointCount = static_cast<uint32_t>(end - begin),
                            .firstBody = static_cast<uint32_t>(clusterBodies_.size())};
            for (size_t i = begin; i < end; ++i) {
                const uint32_t j = order[i];
                clusterJoints_.push_back(j);
                for (const uint32_t b : {joints[j].body0, joints[j].body1}) {
                    const auto first = clusterBodies_.begin() + cluster.firstBody;
                    if (bodies[b].isDynamic() && std::find(first, clusterBodies_.end(), b) == clusterBodies_.end())
                        clusterBodies_.push_back(b);
                }
            }
            cluster.bodyCount = static_cast<uint32_t>(clusterBodies_.size() - cluster.firstBody);
            largestBodies = std::max<size_t>(largestBodies, cluster.bodyCount);
            clusters_.push_back(cluster);
        }
        begin = end;
    }
    // Clusters in the order of their first joint (the sort above went by set root).
    std::sort(clusters_.begin(), clusters_.end(), [&](const Cluster& a, const Cluster& b) {
        return clusterJoints_[a.firstJoint] < clusterJoints_[b.firstJoint];
    });
    if (clusters_.empty()) {
        clusterOf_.clear();
        return;
    }
    for (uint32_t c = 0; c < clusters_.size(); ++c)
        for (uint32_t k = 0; k < clusters_[c].jointCount; ++k) clusterOf_[clusterJoints_[clusters_[c].firstJoint + k]] = c;
    if (!scratch_) scratch_ = std::make_unique<Scratch>();
    scratch_->bodies.resize(std::max(scratch_->bodies.size(), largestBodies));
}

void JointBlockSolver::solveCluster(SolverContext& ctx, std::span<Joint> joints, const Cluster& cluster) {
    Scratch& s = *scratch_;
    JointRows& rows = s.rows;
    rows.count = 0;
    for (uint32_t k = 0; k < cluster.jointCount; ++k)
        appendJointRows(joints[clusterJoints_[cluster.firstJoint + k]], ctx, rows);
    const int n = rows.count;
    if (n == 0) return;

    // W: inverse masses and world inverse inertias, on the poses the Jacobian is taken on.
    const int bodyCount = static_cast<int>(cluster.bodyCount);
    BodyWeights* weights = s.bodies.data();
    for (int b = 0; b < bodyCount; ++b) {
        const uint32_t index = clusterBodies_[cluster.firstBody + b];
        const Body& body = ctx.bodies[index];
        BodyWeights& w = weights[b];
        w.index = index;
        w.invMass = body.invMass;
        w.invInertia = Mat3::Zero();
        if (body.rotates() && body.invMass > 0.0) {
            const Mat3 r = directionOrientation(ctx, body).toRotationMatrix();
            w.invInertia = r * body.invInertia.asDiagonal() * r.transpose();
        }
        w.dx.setZero();
        w.dtheta.setZero();
    }

    // J: each row's two sides, with body 1's signs flipped (it receives the opposite impulse).
    for (int i = 0; i < n; ++i) {
        const JointRow& row = rows.rows[i];
        s.lambda[i] = row.impulse->dot(row.direction);
        for (int side = 0; side < 2; ++side) {
            RowSide& r = s.sides[i][side];
            r.body = findBody(weights, bodyCount, side == 0 ? row.body0 : row.body1);
            const double sign = side == 0 ? 1.0 : -1.0;
            if (row.angular) {
                r.linear.setZero();
                r.angular = sign * row.direction;
            } else {
                r.linear = sign * row.direction;
                r.angular = sign * (side == 0 ? row.arm0 : row.arm1).cross(row.direction);
            }
            r.weightedAngular = r.body >= 0 ? Vec3(weights[r.body].invInertia * r.angular) : Vec3::Zero();
        }
    }
    // A = J W Jᵀ + α̃ and Eq. 4's right-hand side c − α̃ λ for every row.
    s.a.resize(n, n);  // within the fixed capacity: nothing allocated
    for (int i = 0; i < n; ++i) {
        for (int j = i; j < n; ++j) {
            double sum = 0.0;
            for (const RowSide& ri : s.sides[i]) {
                if (ri.body < 0) continue;
                for (const RowSide& rj : s.sides[j])
                    if (rj.body == ri.body)
                        sum += weights[ri.body].invMass * ri.linear.dot(rj.linear) +
                               ri.angular.dot(rj.weightedAngular);
            }
            s.a(i, j) = sum;
            s.a(j, i) = sum;
        }
    }
    s.rhs.resize(n);
    s.scale.resize(n);
    for (int i = 0; i < n; ++i) {
        const JointRow& row = rows.rows[i];
        const double alphaTilde = row.compliance * ctx.invH2;
        s.a(i, i) += alphaTilde;
        s.rhs[i] = row.violation - alphaTilde * s.lambda[i];  // Eq. 4
        s.active[i] = s.a(i, i) > 0.0;  // a row between two bodies that cannot move has nothing to do
        s.scale[i] = s.active[i] ? 1.0 / std::sqrt(s.a(i, i)) : 0.0;
    }

    // Solve, dropping inequality rows whose λ would pull, until none does.
    for (int pass = 0; pass <= n; ++pass) {
        s.scaled.resize(n, n);
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j)
                s.scaled(i, j) = s.active[i] && s.active[j] ? s.scale[i] * s.a(i, j) * s.scale[j] : 0.0;
        for (int i = 0; i < n; ++i) s.scaled(i, i) = s.active[i] ? 1.0 + kRegularisation : 1.0;
        s.ldlt.compute(s.scaled);
        s.step = s.scale.cwiseProduct(s.ldlt.solve(s.scale.cwiseProduct(s.rhs)));
        if (!s.step.allFinite()) return;  // guard: leave the cluster as it is this substep
        bool dropped = false;
        for (int i = 0; i < n; ++i) {
            if (!s.active[i]) s.step[i] = 0.0;
            else if (rows.rows[i].inequality && s.lambda[i] + s.step[i] < 0.0) s.active[i] = false, dropped = true;
        }
        if (!dropped) break;
    }

    // Eqs. 6-9 (positional rows) and Eqs. 15-16 (angular rows) for the summed Δλ; each part
    // keeps its λ and impulse for the readouts (Eq. 10, Eq. 17).
    for (int i = 0; i < n; ++i) {
        const double step = s.step[i];
        if (step == 0.0) continue;
        const JointRow& row = rows.rows[i];
        for (const RowSide& r : s.sides[i]) {
            if (r.body < 0) continue;
            weights[r.body].dx += weights[r.body].invMass * step * r.linear;
            weights[r.body].dtheta += step * r.weightedAngular;
        }
        *row.impulse += step * row.direction;
        if (row.vectorLambda != nullptr) *row.vectorLambda += step * row.direction;
        if (row.scalarLambda != nullptr) *row.scalarLambda += step;
    }
    for (int b = 0; b < bodyCount; ++b) {
        Body& body = ctx.bodies[weights[b].index];
        body.x += weights[b].dx;
        if (body.rotates()) integrateRotation(body.q, weights[b].dtheta);
    }
}

}  // namespace substep
