#include "physics/contact_patch.h"

#include "physics/contact_kinematics.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace substep::contact_detail {
namespace {

/// A 3-vector of the patch solve held as three scalars. Eigen builds the Vec3 that a cross
/// product or a rotation returns with three scalar stores and reads two of them back as one
/// pair for the next vector operation: a load that two stores cannot forward, a stall at
/// every lever arm, row and point velocity of a patch. These are Eigen's operations in
/// Eigen's order (a dot product (x x' + y y') + z z', a rotation u = 2 q⃗ × v, then
/// v + w u + q⃗ × u), so every result has the same bits. No default member values: a
/// PatchSystem holds 55 of them, filled as rows are added (Triple{} is zero).
struct Triple {
    double x;
    double y;
    double z;
};

inline Triple triple(const Vec3& v) { return {v.x(), v.y(), v.z()}; }
inline Vec3 vec3(const Triple& t) { return Vec3(t.x, t.y, t.z); }
inline Triple operator+(const Triple& a, const Triple& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Triple operator-(const Triple& a, const Triple& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Triple operator*(double s, const Triple& a) { return {s * a.x, s * a.y, s * a.z}; }
inline Triple& operator+=(Triple& a, const Triple& b) { return a = a + b; }
inline double dot(const Triple& a, const Triple& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Triple cross(const Triple& a, const Triple& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double norm(const Triple& a) { return std::sqrt(dot(a, a)); }
inline Triple rotate(const Quat& q, const Triple& v) {
    const Triple axis{q.x(), q.y(), q.z()};
    Triple u = cross(axis, v);
    u += u;
    return v + q.w() * u + cross(axis, u);
}

/// Eq. 27: where a body's point was before this substep's integration (previousPoint).
inline Triple previousTriple(const Body& b, const Triple& local) { return triple(b.xPrev) + rotate(b.qPrev, local); }

/// Velocity of a body's point at world offset r (pointVelocity).
inline Triple velocityAt(const Vec3& v, const Vec3& omega, const Triple& r) { return triple(v) + cross(triple(omega), r); }

/// A patch of three or more points spans an area: its static friction is anchored (contact.h).
constexpr int kAreaPoints = 3;

/// Rows of one patch: a normal row per point, two tangent rows and a twist row at its centre.
constexpr int kMaxPatchRows = kMaxPatchPoints + 3;

/// A row whose pivot falls below this fraction of its diagonal depends on the rows before it.
constexpr double kDependentPivot = 1e-9;

/// PatchSystem::shiftOut: a null vector's component below this (of the dependent row's 1) is
/// too small to shift along, and K z must vanish to this fraction of its terms' sizes.
constexpr double kNullComponent = 1e-6;
constexpr double kNullResidual = 1e-10;

/// Solves the symmetric positive semi-definite system a x = b (m x m) by LDLᵀ, skipping rows
/// that depend on earlier ones: a patch's system is singular (four coplanar points fix only
/// three motions), and a dependent row's x is set to zero. Every solution of the consistent
/// rows gives the bodies the same impulse, so which point takes the load does not matter;
/// a dependent row that disagrees (rounding, or points of different triangles) is ignored
/// rather than blown up. Only the lower triangle of a is read; it is overwritten with L.
/// Instantiated for every size so that the compiler unrolls the loops and keeps the factor in
/// registers: the loops over a run-time m took a fifth of pyramid10's step. GCC still kept
/// the inner loops and paired d[k], x[k] into one load from two separate stores, which the
/// stores cannot forward (a stall per pair): every loop is unrolled by pragma, and the solution
/// is built in a local array, which x might alias. A tenth of pyramid10's step, same bits.
template <int m>
[[gnu::always_inline]] inline void solveSemidefiniteFixed(double (&a)[kMaxPatchRows][kMaxPatchRows], const double* b,
                                                          double* x, bool* dependent) {
    double d[m];
    #pragma GCC unroll 11
    for (int j = 0; j < m; ++j) {
        double pivot = a[j][j];
        #pragma GCC unroll 11
        for (int k = 0; k < j; ++k) pivot -= a[j][k] * a[j][k] * d[k];
        dependent[j] = !(pivot > kDependentPivot * a[j][j]);
        d[j] = dependent[j] ? 0.0 : pivot;
        #pragma GCC unroll 11
        for (int i = j + 1; i < m; ++i) {
            if (dependent[j]) {
                a[i][j] = 0.0;
                continue;
            }
            double value = a[i][j];
            #pragma GCC unroll 11
            for (int k = 0; k < j; ++k) value -= a[i][k] * a[j][k] * d[k];
            a[i][j] = value / pivot;
        }
    }
    double y[m];
    #pragma GCC unroll 11
    for (int i = 0; i < m; ++i) {
        double value = b[i];
        #pragma GCC unroll 11
        for (int k = 0; k < i; ++k) value -= a[i][k] * y[k];
        y[i] = dependent[i] ? 0.0 : value;
    }
    double solution[m];
    #pragma GCC unroll 11
    for (int i = m - 1; i >= 0; --i) {
        double value = dependent[i] ? 0.0 : y[i] / d[i];
        #pragma GCC unroll 11
        for (int k = i + 1; k < m; ++k) value -= a[k][i] * solution[k];
        solution[i] = dependent[i] ? 0.0 : value;
    }
    #pragma GCC unroll 11
    for (int i = 0; i < m; ++i) x[i] = solution[i];
}

static_assert(kMaxPatchRows == 11, "solveSemidefinite dispatches sizes 1 to 11");

/// solveSemidefiniteFixed for a size known only at run time (1 to kMaxPatchRows); `dependent`
/// receives which rows were skipped.
void solveSemidefinite(int m, double (&a)[kMaxPatchRows][kMaxPatchRows], const double* b, double* x,
                       bool* dependent) {
    switch (m) {
    case 1: return solveSemidefiniteFixed<1>(a, b, x, dependent);
    case 2: return solveSemidefiniteFixed<2>(a, b, x, dependent);
    case 3: return solveSemidefiniteFixed<3>(a, b, x, dependent);
    case 4: return solveSemidefiniteFixed<4>(a, b, x, dependent);
    case 5: return solveSemidefiniteFixed<5>(a, b, x, dependent);
    case 6: return solveSemidefiniteFixed<6>(a, b, x, dependent);
    case 7: return solveSemidefiniteFixed<7>(a, b, x, dependent);
    case 8: return solveSemidefiniteFixed<8>(a, b, x, dependent);
    case 9: return solveSemidefiniteFixed<9>(a, b, x, dependent);
    case 10: return solveSemidefiniteFixed<10>(a, b, x, dependent);
    case 11: return solveSemidefiniteFixed<11>(a, b, x, dependent);
    default: return;
    }
}

/// One scalar constraint row: body 0 moves along `linear` and turns about `angular0` (r0 × d
/// for a push d at offset r0), body 1 the opposite way. `turn0`, `turn1` are the inverse
/// inertias applied to the angular parts.
struct Row {
    Triple linear;
    Triple angular0;
    Triple angular1;
    Triple turn0;
    Triple turn1;
};

/// The small system of one pair's patch, K x = rhs, where K_ij = l_i·l_j (1/m0 + 1/m1) +
/// a0_i·I0⁻¹a0_j + a1_i·I1⁻¹a1_j is the relative motion along row i per unit multiplier of row
/// j (Eq. 2 plus Eq. 3, or Eq. 11 plus Eq. 12, are its diagonal entries). Solving the rows of a patch together is
/// what lets a box rest: point by point, the push at one corner turns the box and sinks the
/// others, and a friction push at the contact plane tips the box; the next correction tips it
/// back and moves the contact sideways, so the patch never settles (a pyramid's bottom row
/// crept 10 cm in 5 s). With one row the solve is the paper's scalar update.
class PatchSystem {
public:
    PatchSystem(const Body& b0, const Body& b1) {
        linearInverseMass_ = b0.invMass + b1.invMass;
        turns0_ = inertiaKind(b0);
        turns1_ = inertiaKind(b1);
        if (turns0_ == Turns::Rotated) inverseInertia0_ = worldInverseInertia(b0);
        if (turns1_ == Turns::Rotated) inverseInertia1_ = worldInverseInertia(b1);
        scalarInverseInertia0_ = b0.invInertia.x();
        scalarInverseInertia1_ = b1.invInertia.x();
    }

    /// A positional row: a push along unit d at world offsets r0, r1. Returns its index.
    int addPush(const Triple& d, const Triple& r0, const Triple& r1) {
        return addRow(d, cross(r0, d), cross(r1, d));
    }
    /// An angular row: a turn about unit n.
    int addTurn(const Triple& n) { return addRow(Triple{}, n, n); }

    int count() const { return count_; }
    const Row& row(int i) const { return rows_[i]; }

    /// Fills K once every row is added.
    void assemble() {
        for (int i = 0; i < count_; ++i)
            for (int j = i; j < count_; ++j) {
                k_[i][j] = k_[j][i] = dot(rows_[i].linear, rows_[j].linear) * linearInverseMass_ +
                                      dot(rows_[i].angular0, rows_[j].turn0) +
                                      dot(rows_[i].angular1, rows_[j].turn1);
            }
    }

    /// Solves the rows marked `active` of K x = rhs exactly, the other rows' x held at their
    /// given values (zero for a dropped row, the bound for a clamped one). Gauss-Seidel on the
    /// same rows left a residual tip after 8 sweeps that a stack of ten boxes amplified until
    /// it fell.
    void solve(const bool* active, const double* rhs, double* x) {
        int m = 0;
        int held = 0;
        int heldIndex[kMaxPatchRows];
        for (int i = 0; i < count_; ++i) {
            if (active[i]) index_[m++] = i;
            else heldIndex[held++] = i;
        }
        factorRows_ = m;
        if (m == 0) return;
        double b[kMaxPatchRows];
        for (int r = 0; r < m; ++r) {
            const int i = index_[r];
            double value = rhs[i];
            // The held rows in index order, as a list: a test of every row's flag here was
            // a branch mispredicted with every active set.
            for (int h = 0; h < held; ++h) value -= k_[i][heldIndex[h]] * x[heldIndex[h]];
            b[r] = value;
            for (int c = 0; c <= r; ++c) factor_[r][c] = k_[i][index_[c]];  // the lower triangle is all it reads
        }
        double solution[kMaxPatchRows];
        solveSemidefinite(m, factor_, b, solution, dependent_);
        for (int r = 0; r < m; ++r) x[index_[r]] = solution[r];
    }

    /// After solve(), takes row `row` out of the active set with x_row = `target` without solving
    /// again: with one dependent row, K has a null vector z (Lᵀ z = e_dependent, K z = L D Lᵀ z
    /// = 0), and x + t z, t = (target − x_row) / z_row, moves no row: a new solve's solution, to
    /// rounding, once the rows left are independent. A box face's fourth corner is dependent;
    /// the other three hold the centre of pressure half the time, and the corner outside leaves
    /// (half of pyramid10's solves). False, x untouched, where it does not apply (no solve since,
    /// not one dependent row, z_row = 0, or K z not zero to rounding: rows nearly dependent).
    bool shiftOut(int row, double target, double* x) {
        const int m = factorRows_;
        factorRows_ = 0;  // the factor is of the old active set from here on
        int position = -1;
        int dependentPosition = -1;
        for (int r = 0; r < m; ++r) {
            if (index_[r] == row) position = r;
            if (dependent_[r]) {
                if (dependentPosition >= 0) return false;
                dependentPosition = r;
            }
        }
        if (position < 0 || dependentPosition < position) return false;
        double z[kMaxPatchRows];
        z[dependentPosition] = 1.0;
        for (int k = dependentPosition - 1; k >= 0; --k) {
            double value = 0.0;
            for (int i = k + 1; i <= dependentPosition; ++i) value -= factor_[i][k] * z[i];
            z[k] = value;
        }
        if (!(std::abs(z[position]) > kNullComponent)) return false;
        for (int i = 0; i < count_; ++i) {
            double sum = 0.0;
            double scale = 0.0;
            for (int r = 0; r <= dependentPosition; ++r) {
                const double term = k_[i][index_[r]] * z[r];
                sum += term;
                scale += std::abs(term);
            }
            if (!(std::abs(sum) <= kNullResidual * scale)) return false;
        }
        const double t = (target - x[row]) / z[position];
        for (int r = 0; r <= dependentPosition; ++r) x[index_[r]] += t * z[r];
        x[row] = target;
        return true;
    }

    /// The motion along row i that the multipliers x make: (K x)_i.
    double motion(int i, const double* x) const {
        double sum = 0.0;
        for (int j = 0; j < count_; ++j) sum += k_[i][j] * x[j];
        return sum;
    }

    /// Σ x_i l_i and the angular impulses Σ x_i a_i on each body.
    void impulses(int rows, const double* x, Vec3& linear, Vec3& angular0, Vec3& angular1) const {
        Triple sum{}, sum0{}, sum1{};
        for (int i = 0; i < rows; ++i) {
            sum += x[i] * rows_[i].linear;
            sum0 += x[i] * rows_[i].angular0;
            sum1 += x[i] * rows_[i].angular1;
        }
        linear = vec3(sum);
        angular0 = vec3(sum0);
        angular1 = vec3(sum1);
    }

private:
    /// How a body turns under an angular impulse: not at all (static, or a particle), by a
    /// scalar I⁻¹ (equal principal moments: cubes, spheres; no world matrix needed), or by
    /// R I⁻¹ Rᵀ.
    enum class Turns : uint8_t { No, Scalar, Rotated };
    static Turns inertiaKind(const Body& b) {
        if (!b.rotates() || !(b.invMass > 0.0)) return Turns::No;
        return b.isotropic ? Turns::Scalar : Turns::Rotated;
    }
    static Triple turn(Turns kind, double scalar, const Mat3& rotated, const Triple& angular) {
        switch (kind) {
        case Turns::Scalar: return scalar * angular;
        case Turns::Rotated: return triple(rotated * vec3(angular));
        default: return Triple{};
        }
    }

    static Mat3 worldInverseInertia(const Body& b) {
        const Mat3 r = b.q.toRotationMatrix();
        return r * b.invInertia.asDiagonal() * r.transpose();
    }

    int addRow(const Triple& linear, const Triple& angular0, const Triple& angular1) {
        Row& row = rows_[count_];
        row.linear = linear;
        row.angular0 = angular0;
        row.angular1 = angular1;
        row.turn0 = turn(turns0_, scalarInverseInertia0_, inverseInertia0_, angular0);
        row.turn1 = turn(turns1_, scalarInverseInertia1_, inverseInertia1_, angular1);
        return count_++;
    }

    double linearInverseMass_ = 0.0;
    Turns turns0_ = Turns::No;
    Turns turns1_ = Turns::No;
    double scalarInverseInertia0_ = 0.0;
    double scalarInverseInertia1_ = 0.0;
    Mat3 inverseInertia0_;  // set only for Turns::Rotated
    Mat3 inverseInertia1_;
    Row rows_[kMaxPatchRows];
    double k_[kMaxPatchRows][kMaxPatchRows];
    int count_ = 0;
    // The last solve's factor (L below the diagonal) of the active rows index_[0, factorRows_),
    // and which of them it skipped as dependent; factorRows_ = 0 once it no longer applies.
    double factor_[kMaxPatchRows][kMaxPatchRows];
    int index_[kMaxPatchRows];
    bool dependent_[kMaxPatchRows];
    int factorRows_ = 0;
};

/// The centre of a patch's points on each body (principal frames), their mean normal and
/// their mean distance from the centre across it (the lever arm of torsional friction).
struct Patch {
    Triple centre0{};
    Triple centre1{};
    Triple normal{};
    double radius = 0.0;
    int points = 0;
};

/// The mean distance across the normal of the points `use` selects from the patch's centre
/// (Patch::radius), for a patch of two or more points.
template <class Use>
double patchRadius(std::span<const Contact> contacts, const Body& b0, const Patch& patch, Use&& use) {
    double radius = 0.0;
    for (const Contact& c : contacts) {
        if (!use(c)) continue;
        const Triple offset = rotate(b0.q, triple(c.local0) - patch.centre0);
        radius += norm(offset - dot(offset, patch.normal) * patch.normal);
    }
    return radius / patch.points;
}

/// The patch of the points `use` selects; its radius only if `withRadius` (the velocity pass
/// needs it only for a patch that is not at rest).
template <class Use>
Patch patchOf(std::span<const Contact> contacts, const Body& b0, Use&& use, bool withRadius = true) {
    Patch patch;
    for (const Contact& c : contacts) {
        if (!use(c)) continue;
        patch.centre0 += triple(c.local0);
        patch.centre1 += triple(c.local1);
        patch.normal += triple(c.normal);
        ++patch.points;
    }
    if (patch.points == 0) return patch;
    const double points = patch.points;
    patch.centre0 = {patch.centre0.x / points, patch.centre0.y / points, patch.centre0.z / points};
    patch.centre1 = {patch.centre1.x / points, patch.centre1.y / points, patch.centre1.z / points};
    const double length = norm(patch.normal);
    if (!(length > kDirectionEpsilon)) {
        patch.points = 0;  // opposing normals: no common tangent plane to hold
        return patch;
    }
    patch.normal = {patch.normal.x / length, patch.normal.y / length, patch.normal.z / length};
    if (withRadius && patch.points > 1) patch.radius = patchRadius(contacts, b0, patch, use);
    return patch;
}

/// The friction rows of a patch: two tangent pushes at its centre and, where it has a lever
/// arm, a turn about its normal. Returns the index of the first tangent row.
int addFrictionRows(PatchSystem& system, const Patch& patch, const Triple& r0, const Triple& r1,
                    Triple& t1, Triple& t2, int& spinRow) {
    t1 = triple(anyPerpendicular(vec3(patch.normal)));
    t2 = cross(patch.normal, t1);
    const int first = system.addPush(t1, r0, r1);
    system.addPush(t2, r0, r1);
    spinRow = patch.radius > 0.0 ? system.addTurn(patch.normal) : -1;
    return first;
}

void moveVelocities(Body& b0, Body& b1, const Vec3& linear, const Vec3& angular0,
                    const Vec3& angular1) {
    if (b0.invMass > 0.0) {
        b0.v += linear * b0.invMass;
        if (b0.rotates()) b0.omega += b0.applyInverseInertia(angular0);
    }
    if (b1.invMass > 0.0) {
        b1.v -= linear * b1.invMass;
        if (b1.rotates()) b1.omega -= b1.applyInverseInertia(angular1);
    }
}

/// The pushes of a patch as a small active set: points that would be pulled (total λ_n < 0)
/// leave the set, points that the others' pushes sink into contact join it, until neither
/// happens (or every point had its turn twice).
void solvePushes(PatchSystem& system, std::span<const Contact> contacts, const double* depth,
                 bool* active, double* x) {
    const int points = static_cast<int>(contacts.size());
    bool solved = false;  // x already solves the active set (PatchSystem::shiftOut)
    for (int round = 0; round <= 2 * points; ++round) {
        if (!solved) system.solve(active, depth, x);
        solved = false;
        int leaving = -1;
        double mostNegative = 0.0;
        for (int i = 0; i < points; ++i) {
            const double total = contacts[i].lambdaNormal + x[i];
            if (active[i] && total < mostNegative) mostNegative = total, leaving = i;
        }
        if (leaving >= 0) {
            active[leaving] = false;
            const double target = -contacts[leaving].lambdaNormal;  // the total λ_n drops to zero
            solved = system.shiftOut(leaving, target, x);
            if (!solved) x[leaving] = target;
            continue;
        }
        int joining = -1;
        double deepest = 1e-12;
        for (int i = 0; i < points; ++i) {
            const double remaining = depth[i] - system.motion(i, x);
            if (!active[i] && x[i] == 0.0 && remaining > deepest) deepest = remaining, joining = i;
        }
        if (joining < 0) return;
        active[joining] = true;
    }
}

}  // namespace

void solvePatchPositions(ContactPair& pair, std::span<Contact> contacts, SolverContext& ctx) {
    const Body& b0 = ctx.bodies[pair.body0];
    const Body& b1 = ctx.bodies[pair.body1];
    const int points = static_cast<int>(contacts.size());

    // Eq. 26: the depth of every point on the current poses; only a penetrating patch acts.
    PatchSystem system(b0, b1);
    double rhs[kMaxPatchRows] = {};
    bool penetrates = false;
    const Triple x0 = triple(b0.x);
    const Triple x1 = triple(b1.x);
    for (int i = 0; i < points; ++i) {
        const Contact& c = contacts[i];
        const Triple r0 = rotate(b0.q, triple(c.local0));
        const Triple r1 = rotate(b1.q, triple(c.local1));
        const Triple n = triple(c.normal);
        system.addPush(n, r0, r1);
        rhs[i] = pushOut(dot((x1 + r1) - (x0 + r0), n), b0, b1, vec3(r0), vec3(r1), c.normal, ctx);
        penetrates = penetrates || rhs[i] > 0.0;
    }
    if (!penetrates) return;

    // Eq. 27 and Eq. 28 for the patch: the tangential motion of its centre during this substep, and
    // its turn about the normal, are undone together with the pushes, and kept only while
    // λ_t ≤ μ_s Σλ_n (and the turn within μ_s Σλ_n times the lever arm). See contact.h for
    // why not corner by corner.
    const Patch patch = patchOf(contacts.first(points), b0, [](const Contact&) { return true; });
    int tangentRow = -1;
    int spinRow = -1;
    if (pair.staticFriction > 0.0 && patch.points > 0) {
        // What static friction undoes: for an area patch, the slip and turn since its anchors
        // were set; for one or two points, the motion during this substep (Eq. 27).
        const bool area = patch.points >= kAreaPoints;
        if (!area) pair.anchored = false;
        if (area && !pair.anchored) {
            pair.anchor0 = vec3(patch.centre0);
            pair.anchor1 = b1.qPrev.conjugate() * (previousPoint(b0, pair.anchor0) - b1.xPrev);
            pair.turnAnchor = (b0.qPrev.conjugate() * b1.qPrev).normalized();
            pair.anchored = true;
        }
        const Triple local0 = area ? triple(pair.anchor0) : patch.centre0;
        const Triple r0 = rotate(b0.q, local0);
        const Triple r1 = rotate(b1.q, area ? triple(pair.anchor1) : patch.centre1);
        Triple t1, t2;
        tangentRow = addFrictionRows(system, patch, r0, r1, t1, t2, spinRow);
        const Triple slip = area ? (x0 + r0) - (x1 + r1)
                                 : (x0 + r0 - previousTriple(b0, local0)) -
                                       (x1 + r1 - previousTriple(b1, patch.centre1));
        rhs[tangentRow] = -dot(slip, t1);
        rhs[tangentRow + 1] = -dot(slip, t2);
        if (spinRow >= 0) {
            const Quat turn = area ? Quat(b0.q * pair.turnAnchor * b1.q.conjugate())
                                   : Quat((b0.q * b0.qPrev.conjugate()) * (b1.q * b1.qPrev.conjugate()).conjugate());
            rhs[spinRow] = -dot(triple(rotationVector(turn.normalized())), patch.normal);
        }
    }
    system.assemble();

    double x[kMaxPatchRows] = {};
    bool active[kMaxPatchRows] = {};
    for (int i = 0; i < points; ++i) active[i] = rhs[i] > 0.0;
    for (int i = points; i < system.count(); ++i) active[i] = true;
    solvePushes(system, contacts.first(points), rhs, active, x);
    if (tangentRow >= 0) {
        double normalSum = 0.0;
        for (int i = 0; i < points; ++i) normalSum += contacts[i].lambdaNormal + x[i];
        const double limit = pair.staticFriction * normalSum;
        const double tangent = planarLength(pair.lambdaTangent1 + x[tangentRow], pair.lambdaTangent2 + x[tangentRow + 1]);
        const bool spinHolds = spinRow < 0 || std::abs(pair.lambdaTwist + x[spinRow]) <= limit * patch.radius;
        if (tangent <= limit && spinHolds) {
            pair.lambdaTangent1 += x[tangentRow];
            pair.lambdaTangent2 += x[tangentRow + 1];
            if (spinRow >= 0) pair.lambdaTwist += x[spinRow];
        } else {
            // Static friction gives way: the pushes alone, and the velocity pass's dynamic
            // friction takes over (paper 3.5). The anchors let go.
            pair.anchored = false;
            for (int i = points; i < system.count(); ++i) active[i] = false, x[i] = 0.0;
            solvePushes(system, contacts.first(points), rhs, active, x);
        }
    }
    Vec3 linear, angular0, angular1;
    system.impulses(system.count(), x, linear, angular0, angular1);
    applyImpulse(ctx, pair.body0, pair.body1, linear, angular0, angular1);
    pair.lambdaNormal = 0.0;
    for (int i = 0; i < points; ++i) {
        contacts[i].lambdaNormal += x[i];
        pair.lambdaNormal += contacts[i].lambdaNormal;
    }
}

void solvePatchVelocities(const ContactPair& pair, std::span<const Contact> contacts, Body& b0, Body& b1,
                          double h, double gravity) {
    const int points = static_cast<int>(contacts.size());
    const auto pushed = [](const Contact& c) { return c.lambdaNormal > 0.0; };
    Patch patch = patchOf(contacts.first(points), b0, pushed, false);
    if (patch.points == 0) return;

    // Eq. 34 at every point that pushed: the normal velocity PBD derived (it reflects the
    // push-out, not the motion) becomes −e v̄_n, v̄_n from the velocities before this
    // substep's derivation. Bodies created overlapping have v̄_n ≈ 0 and separate without
    // flying apart (Fig. 13). Below twice the speed gravity adds in one substep there is no
    // bounce (the paper's jitter guard). The change may pull: it removes a push-out's speed.
    const double restingSpeed = 2.0 * gravity * h;
    double rhs[kMaxPatchRows] = {};
    Triple r0s[kMaxPatchPoints];
    Triple r1s[kMaxPatchPoints];
    int normals[kMaxPatchPoints];
    int rows = 0;
    double largestChange = 0.0;
    for (int i = 0; i < points; ++i) {
        const Contact& c = contacts[i];
        if (!pushed(c)) continue;
        const Triple r0 = rotate(b0.q, triple(c.local0));
        const Triple r1 = rotate(b1.q, triple(c.local1));
        const Triple n = triple(c.normal);
        const double vn = dot(velocityAt(b0.v, b0.omega, r0) - velocityAt(b1.v, b1.omega, r1), n);  // Eq. 29
        const double vnBefore = dot(velocityAt(b0.vPrev, b0.omegaPrev, r0) - velocityAt(b1.vPrev, b1.omegaPrev, r1), n);
        const double e = std::abs(vnBefore) <= restingSpeed ? 0.0 : pair.restitution;
        r0s[rows] = r0;
        r1s[rows] = r1;
        normals[rows] = i;
        rhs[rows] = std::max(-e * vnBefore, 0.0) - vn;  // Eq. 34
        largestChange = std::max(largestChange, std::abs(rhs[rows]));
        ++rows;
    }

    // Eq. 30 with ERRATA item 2, for the patch: the friction impulse is at most
    // h μ_d |f_n| = μ_d Σλ_n / h, with f_n = λ_n / h² (Eq. 10) (a disc, so friction is isotropic), and the spin about the
    // normal is slowed by at most that times the lever arm.
    const bool friction = pair.dynamicFriction > 0.0;
    const Triple r0 = rotate(b0.q, patch.centre0);
    const Triple r1 = rotate(b1.q, patch.centre1);
    const Triple slip = velocityAt(b0.v, b0.omega, r0) - velocityAt(b1.v, b1.omega, r1);
    const Triple tangentialSlip = slip - dot(slip, patch.normal) * patch.normal;
    const double spin = dot(triple(b0.omega) - triple(b1.omega), patch.normal);
    if (friction) {
        largestChange = std::max(largestChange, norm(tangentialSlip));
        // The lever arm only where the rest test or the solve needs it: no point is farther
        // from the centre than `reach`, and a patch that rests with that lever arm rests.
        if (patch.points > 1 && !(largestChange > kRestingSpeed)) {
            double reach2 = 0.0;
            for (const Contact& c : contacts.first(points))
                if (pushed(c)) {
                    const Triple offset = triple(c.local0) - patch.centre0;
                    reach2 = std::max(reach2, dot(offset, offset));
                }
            if (!(std::abs(spin) * std::sqrt(reach2) > kRestingSpeed)) return;
        }
        if (patch.points > 1) patch.radius = patchRadius(contacts.first(points), b0, patch, pushed);
        largestChange = std::max(largestChange, std::abs(spin) * patch.radius);
    }
    // A patch at rest (a stack standing) has nothing to change: skip its solve.
    if (!(largestChange > kRestingSpeed)) return;

    PatchSystem system(b0, b1);
    for (int row = 0; row < rows; ++row) system.addPush(triple(contacts[normals[row]].normal), r0s[row], r1s[row]);
    int tangentRow = -1;
    int spinRow = -1;
    if (friction) {
        Triple t1, t2;
        tangentRow = addFrictionRows(system, patch, r0, r1, t1, t2, spinRow);
        rhs[tangentRow] = -dot(slip, t1);
        rhs[tangentRow + 1] = -dot(slip, t2);
        if (spinRow >= 0) rhs[spinRow] = -spin;
    }
    system.assemble();
    double x[kMaxPatchRows] = {};
    bool active[kMaxPatchRows];
    std::fill(std::begin(active), std::end(active), true);  // the whole array: GCC 12 cannot bound count()
    system.solve(active, rhs, x);
    if (tangentRow >= 0) {
        // Friction beyond its bound is held at the bound, and the normal rows solved again.
        const double limit = pair.dynamicFriction * pair.lambdaNormal / h;
        bool clamped = false;
        const double tangent = planarLength(x[tangentRow], x[tangentRow + 1]);
        if (tangent > limit) {
            x[tangentRow] *= limit / tangent;
            x[tangentRow + 1] *= limit / tangent;
            active[tangentRow] = active[tangentRow + 1] = false;
            clamped = true;
        }
        if (spinRow >= 0 && std::abs(x[spinRow]) > limit * patch.radius) {
            x[spinRow] = std::copysign(limit * patch.radius, x[spinRow]);
            active[spinRow] = false;
            clamped = true;
        }
        if (clamped) system.solve(active, rhs, x);
    }
    Vec3 linear, angular0, angular1;
    system.impulses(system.count(), x, linear, angular0, angular1);
    moveVelocities(b0, b1, linear, angular0, angular1);
}

}  // namespace substep::contact_detail
