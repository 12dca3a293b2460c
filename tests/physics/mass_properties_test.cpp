// Tests engine/physics/mass_properties.cpp against closed forms and independent integration.

#include "physics/mass_properties.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace substep {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// Closed triangle mesh of a box with full extents `size`, rotated by `rotation` then moved
/// to `center`. Corner i has x, y, z signs from bits 0, 1, 2 of i.
TriangleMesh boxMesh(const Vec3& size, const Vec3& center = Vec3::Zero(),
                     const Quat& rotation = Quat::Identity()) {
    TriangleMesh mesh;
    for (int i = 0; i < 8; ++i) {
        const Vec3 corner(i & 1 ? 0.5 : -0.5, i & 2 ? 0.5 : -0.5, i & 4 ? 0.5 : -0.5);
        mesh.vertices.push_back(center + rotation * corner.cwiseProduct(size));
    }
    // Two counter-clockwise triangles per face: -x, +x, -y, +y, -z, +z.
    mesh.triangles = {{0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}, {0, 1, 5}, {0, 5, 4},
                      {2, 6, 7}, {2, 7, 3}, {0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}};
    return mesh;
}

/// The right tetrahedron (0, e_x, e_y, e_z), faces counter-clockwise from outside.
TriangleMesh unitTetrahedron() {
    return {.vertices = {Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()},
            .triangles = {{0, 2, 1}, {0, 3, 2}, {0, 1, 3}, {1, 2, 3}}};
}

TriangleMesh insideOut(TriangleMesh mesh) {
    for (auto& triangle : mesh.triangles)
        std::swap(triangle[1], triangle[2]);
    return mesh;
}

/// Fixture check: every face normal points away from the centre (so "inside out" means it).
void expectOutwardWinding(const TriangleMesh& mesh, const Vec3& inside) {
    for (const auto& t : mesh.triangles) {
        const Vec3& a = mesh.vertices[t[0]];
        const Vec3 normal = (mesh.vertices[t[1]] - a).cross(mesh.vertices[t[2]] - a);
        EXPECT_GT(normal.dot(a - inside), 0.0);
    }
}

/// Box inertia about its centre: m (b² + c²)/12 and cyclic.
Vec3 boxMoments(const Vec3& size, double mass) {
    const Vec3 s = size.cwiseProduct(size);
    return Vec3(s.y() + s.z(), s.x() + s.z(), s.x() + s.y()) * (mass / 12.0);
}

void expectMatrixNear(const Mat3& actual, const Mat3& expected, double tolerance) {
    EXPECT_LE((actual - expected).norm(), tolerance) << "actual\n"
                                                     << actual << "\nexpected\n"
                                                     << expected;
}

void expectAllFinite(const MassProperties& p) {
    EXPECT_TRUE(std::isfinite(p.mass));
    EXPECT_TRUE(p.centerOfMass.allFinite());
    EXPECT_TRUE(p.inertia.allFinite());
}

// --- Primitives ---------------------------------------------------------------------------

TEST(MassPropertiesTest, SphereMatchesClosedForm) {
    const double r = 0.3, density = 7.0;
    const MassProperties p = sphereMassProperties(r, density);
    const double mass = density * 4.0 / 3.0 * kPi * r * r * r;
    EXPECT_NEAR(p.mass, mass, 1e-14);
    EXPECT_TRUE(p.centerOfMass.isZero());
    expectMatrixNear(p.inertia, Mat3::Identity() * (0.4 * mass * r * r), 1e-15);
}

TEST(MassPropertiesTest, BoxMatchesClosedForm) {
    const Vec3 size(1.0, 2.0, 3.0);
    const MassProperties p = boxMassProperties(size, 2.0);
    EXPECT_NEAR(p.mass, 12.0, 1e-14);
    expectMatrixNear(p.inertia, Mat3(boxMoments(size, 12.0).asDiagonal()), 1e-14);
    // m(b² + c²)/12 spelled out for the first axis: 12 (4 + 9)/12 = 13.
    EXPECT_NEAR(p.inertia(0, 0), 13.0, 1e-14);
}

// Capsule of radius r, segment h (along y): cylinder mass m_c = ρπr²h, two caps m_s = ρ4/3πr³.
// Axial: m_c r²/2 + m_s 2r²/5 (the caps together make a sphere).
// Transverse: cylinder m_c (h²/12 + r²/4). One cap about its flat face: 2/5 m r²; about its
// centroid (3r/8 out): 2/5 m r² - m (3r/8)²; about the capsule centre, at h/2 + 3r/8:
// + m (h/2 + 3r/8)². Summed over both caps: m_s (2r²/5 + h²/4 + 3hr/8).
struct CapsuleFormula {
    double mass, axial, transverse;
};
CapsuleFormula capsuleFormula(double r, double h, double density) {
    const double cylinder = density * kPi * r * r * h;
    const double caps = density * 4.0 / 3.0 * kPi * r * r * r;
    return {cylinder + caps, cylinder * r * r / 2.0 + caps * 2.0 * r * r / 5.0,
            cylinder * (h * h / 12.0 + r * r / 4.0) +
                caps * (2.0 * r * r / 5.0 + h * h / 4.0 + 3.0 * h * r / 8.0)};
}

TEST(MassPropertiesTest, CapsuleMatchesHandDerivedFormula) {
    for (const auto& [r, h] : {std::pair{0.5, 1.0}, std::pair{0.1, 2.0}, std::pair{1.0, 0.2}}) {
        const MassProperties p = capsuleMassProperties(r, h, 3.0);
        const CapsuleFormula f = capsuleFormula(r, h, 3.0);
        EXPECT_NEAR(p.mass, f.mass, 1e-12 * f.mass);
        expectMatrixNear(p.inertia, Mat3(Vec3(f.transverse, f.axial, f.transverse).asDiagonal()),
                         1e-12 * f.transverse);
    }
}

TEST(MassPropertiesTest, CapsuleOfZeroLengthIsASphere) {
    const MassProperties capsule = capsuleMassProperties(0.4, 0.0, 5.0);
    const MassProperties sphere = sphereMassProperties(0.4, 5.0);
    EXPECT_NEAR(capsule.mass, sphere.mass, 1e-14);
    expectMatrixNear(capsule.inertia, sphere.inertia, 1e-14);
}

// Independent of any formula: midpoint-rule integration over a fine voxel grid of the capsule
// (the set of points within r of the segment). Deterministic, so no seed to fix.
TEST(MassPropertiesTest, CapsuleMatchesVoxelIntegration) {
    const double r = 0.5, h = 1.0, density = 2.0;
    const int n = 160;  // cells across the diameter
    const double cell = 2.0 * r / n, dV = cell * cell * cell;
    const int ny = static_cast<int>(std::lround((h + 2.0 * r) / cell));
    double mass = 0.0, ixx = 0.0, iyy = 0.0, izz = 0.0;
    for (int i = 0; i < n; ++i) {
        const double x = -r + (i + 0.5) * cell;
        for (int j = 0; j < ny; ++j) {
            const double y = -(0.5 * h + r) + (j + 0.5) * cell;
            const double dy = y - std::clamp(y, -0.5 * h, 0.5 * h);
            for (int k = 0; k < n; ++k) {
                const double z = -r + (k + 0.5) * cell;
                if (x * x + dy * dy + z * z > r * r) continue;
                mass += density * dV;
                ixx += density * dV * (y * y + z * z);
                iyy += density * dV * (x * x + z * z);
                izz += density * dV * (x * x + y * y);
            }
        }
    }
    const MassProperties p = capsuleMassProperties(r, h, density);
    const double tolerance = 1e-3;  // relative; the grid's error is about 6e-5
    EXPECT_NEAR(p.mass, mass, tolerance * mass);
    EXPECT_NEAR(p.inertia(0, 0), ixx, tolerance * ixx);
    EXPECT_NEAR(p.inertia(1, 1), iyy, tolerance * iyy);
    EXPECT_NEAR(p.inertia(2, 2), izz, tolerance * izz);

    // The check has teeth: the usual slips miss the integral by more than the tolerance.
    const double cylinder = density * kPi * r * r * h;
    const double caps = density * 4.0 / 3.0 * kPi * r * r * r;
    const double cylinderPart = cylinder * (h * h / 12.0 + r * r / 4.0);
    const double capsAtSegmentEnd = caps * (0.4 * r * r + h * h / 4.0);  // centroid not shifted
    const double capsNoCentroidCorrection = caps * (0.4 * r * r + std::pow(h / 2 + 3 * r / 8, 2));
    EXPECT_GT(std::abs(cylinderPart + capsAtSegmentEnd - ixx), tolerance * ixx);
    EXPECT_GT(std::abs(cylinderPart + capsNoCentroidCorrection - ixx), tolerance * ixx);
}

// --- Triangle meshes (Blow and Binstock) ----------------------------------------------------

TEST(MassPropertiesTest, CubeMeshMatchesBoxFormula) {
    const TriangleMesh cube = boxMesh(Vec3::Ones());
    expectOutwardWinding(cube, Vec3::Zero());
    const MassProperties p = meshMassProperties(cube, 3.0);
    EXPECT_NEAR(p.mass, 3.0, 1e-14);
    EXPECT_LE(p.centerOfMass.norm(), 1e-15);
    expectMatrixNear(p.inertia, Mat3::Identity() * (3.0 * 2.0 / 12.0), 1e-14);
}

TEST(MassPropertiesTest, BoxMeshMatchesBoxFormula) {
    const Vec3 size(1.0, 2.0, 3.0);
    const MassProperties p = meshMassProperties(boxMesh(size), 0.5);
    EXPECT_NEAR(p.mass, 3.0, 1e-14);
    expectMatrixNear(p.inertia, Mat3(boxMoments(size, 3.0).asDiagonal()), 1e-13);
}

TEST(MassPropertiesTest, TranslatedCubeKeepsCentralInertia) {
    // (1, 2, 3) as asked, and far away, where sums about the origin would cancel badly.
    for (const Vec3& offset : {Vec3(1.0, 2.0, 3.0), Vec3(1e5, -2e5, 3e5)}) {
        const MassProperties p = meshMassProperties(boxMesh(Vec3::Ones(), offset), 1.0);
        EXPECT_NEAR(p.mass, 1.0, 1e-12);
        EXPECT_LE((p.centerOfMass - offset).norm(), 1e-12 * (1.0 + offset.norm()));
        expectMatrixNear(p.inertia, Mat3::Identity() / 6.0, 1e-10);
    }
}

TEST(MassPropertiesTest, RotatedBoxMeshHasBoxPrincipalMoments) {
    const Vec3 size(1.0, 2.0, 3.0);
    const Quat q(Eigen::AngleAxisd(0.7, Vec3(1.0, 2.0, -0.5).normalized()));
    const Vec3 offset(0.3, -1.0, 2.0);
    const MassProperties p = meshMassProperties(boxMesh(size, offset, q), 1.0);
    EXPECT_NEAR(p.mass, 6.0, 1e-13);
    EXPECT_LE((p.centerOfMass - offset).norm(), 1e-13);

    // The shape-frame tensor is the box's, turned: R_q diag R_qᵀ.
    const Vec3 moments = boxMoments(size, 6.0);  // (13, 10, 5)/2: ascending order is z, y, x
    const Mat3 rq = q.toRotationMatrix();
    expectMatrixNear(p.inertia, rq * moments.asDiagonal() * rq.transpose(), 1e-12);

    const PrincipalFrame frame = principalFrame(p.inertia);
    EXPECT_NEAR(frame.moments.x(), moments.z(), 1e-12);
    EXPECT_NEAR(frame.moments.y(), moments.y(), 1e-12);
    EXPECT_NEAR(frame.moments.z(), moments.x(), 1e-12);
    // Its axes are the box's turned axes (up to sign), and it turns the tensor back to diagonal.
    const Mat3 r = frame.rotation.toRotationMatrix();
    EXPECT_NEAR(std::abs(r.col(0).dot(q * Vec3::UnitZ())), 1.0, 1e-12);
    EXPECT_NEAR(std::abs(r.col(1).dot(q * Vec3::UnitY())), 1.0, 1e-12);
    EXPECT_NEAR(std::abs(r.col(2).dot(q * Vec3::UnitX())), 1.0, 1e-12);
    expectMatrixNear(r.transpose() * p.inertia * r, Mat3(frame.moments.asDiagonal()), 1e-12);
}

TEST(MassPropertiesTest, InsideOutMeshGivesSameResult) {
    const Quat q(Eigen::AngleAxisd(0.4, Vec3(0.0, 1.0, 1.0).normalized()));
    const TriangleMesh mesh = boxMesh(Vec3(1.0, 2.0, 3.0), Vec3(1.0, 2.0, 3.0), q);
    const MassProperties outward = meshMassProperties(mesh, 2.0);
    const MassProperties inward = meshMassProperties(insideOut(mesh), 2.0);
    EXPECT_NEAR(inward.mass, 12.0, 1e-12);
    EXPECT_NEAR(inward.mass, outward.mass, 1e-12);
    EXPECT_LE((inward.centerOfMass - outward.centerOfMass).norm(), 1e-12);
    expectMatrixNear(inward.inertia, outward.inertia, 1e-12);
}

TEST(MassPropertiesTest, TetrahedronMatchesClosedForm) {
    const TriangleMesh tetrahedron = unitTetrahedron();
    expectOutwardWinding(tetrahedron, Vec3::Constant(0.25));
    const MassProperties p = meshMassProperties(tetrahedron, 1.0);
    EXPECT_NEAR(p.mass, 1.0 / 6.0, 1e-15);
    EXPECT_LE((p.centerOfMass - Vec3::Constant(0.25)).norm(), 1e-15);
    // Dirichlet integrals over the simplex: ∫x² = 2!/5! = 1/60, ∫xy = 1/5! = 1/120. About the
    // centroid: ∫x² - V/16 = 1/160, ∫xy - V/16 = -1/480. So I_xx = 2/160, I_xy = +1/480.
    const Mat3 expected = Mat3::Constant(1.0 / 480.0) + Mat3::Identity() * (1.0 / 80 - 1.0 / 480);
    expectMatrixNear(p.inertia, expected, 1e-15);
}

// Unlike the box and the tetrahedron, a pyramid's vertex mean (h/5 up) is not its centroid
// (h/4 up), so this also checks the shift of the covariance to the centre of mass.
TEST(MassPropertiesTest, SquarePyramidMatchesClosedForm) {
    const double a = 2.0, h = 3.0, density = 1.5;
    const Vec3 base(1.0, 2.0, 3.0);  // centre of the base
    TriangleMesh pyramid = {
        .vertices = {{-a / 2, 0, -a / 2},
                     {a / 2, 0, -a / 2},
                     {a / 2, 0, a / 2},
                     {-a / 2, 0, a / 2},
                     {0, h, 0}},
        .triangles = {{0, 1, 2}, {0, 2, 3}, {0, 4, 1}, {1, 4, 2}, {2, 4, 3}, {3, 4, 0}}};
    for (Vec3& v : pyramid.vertices)
        v += base;
    expectOutwardWinding(pyramid, base + Vec3(0, h / 4, 0));

    // Slices are squares of side s = a(1 - y/h): V = a²h/3, ∫x² = ∫ s⁴/12 dy = V a²/20,
    // ∫y = V h/4, ∫y² = V h²/10, so about the centroid ∫y² = 3/80 V h².
    const double mass = density * a * a * h / 3.0;
    const MassProperties p = meshMassProperties(pyramid, density);
    EXPECT_NEAR(p.mass, mass, 1e-13);
    EXPECT_LE((p.centerOfMass - (base + Vec3(0, h / 4, 0))).norm(), 1e-13);
    const double axial = mass * a * a / 10.0;
    const double transverse = mass * (a * a / 20.0 + 3.0 * h * h / 80.0);
    expectMatrixNear(p.inertia, Mat3(Vec3(transverse, axial, transverse).asDiagonal()), 1e-12);
}

TEST(MassPropertiesTest, DegenerateMeshesHaveNoMass) {
    // A square with both sides, i.e. a closed but flat shell, and an empty mesh.
    const TriangleMesh flat = {.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}},
                               .triangles = {{0, 1, 2}, {0, 2, 3}, {0, 2, 1}, {0, 3, 2}}};
    for (const TriangleMesh& mesh : {flat, TriangleMesh{}}) {
        const MassProperties p = meshMassProperties(mesh, 1.0);
        expectAllFinite(p);
        EXPECT_EQ(p.mass, 0.0);
        EXPECT_TRUE(p.inertia.isZero());
    }
}

// --- Dispatch and scaling -----------------------------------------------------------------

TEST(MassPropertiesTest, ShapeDispatch) {
    EXPECT_EQ(shapeMassProperties(sphereShape(0.5), 2.0).mass, sphereMassProperties(0.5, 2.0).mass);
    EXPECT_EQ(shapeMassProperties(boxShape(Vec3(1, 2, 3)), 2.0).mass, 12.0);
    EXPECT_EQ(shapeMassProperties(capsuleShape(0.5, 1.0), 2.0).mass,
              capsuleMassProperties(0.5, 1.0, 2.0).mass);
    Shape mesh;
    mesh.type = ShapeType::Mesh;
    EXPECT_EQ(shapeMassProperties(mesh, 2.0).mass, 0.0);  // no mesh attached
    mesh.mesh = std::make_shared<const TriangleMesh>(boxMesh(Vec3::Ones()));
    EXPECT_NEAR(shapeMassProperties(mesh, 2.0).mass, 2.0, 1e-14);
    for (const Shape& massless : {planeShape(Vec3::UnitY(), 0.0), Shape{}}) {
        const MassProperties p = shapeMassProperties(massless, 2.0);
        expectAllFinite(p);
        EXPECT_EQ(p.mass, 0.0);
        EXPECT_TRUE(p.inertia.isZero());
    }
}

TEST(MassPropertiesTest, WithMassScalesInertia) {
    const Vec3 size(1.0, 2.0, 3.0);
    MassProperties box = boxMassProperties(size, 1.0);
    box.centerOfMass = Vec3(1.0, 2.0, 3.0);
    const MassProperties p = withMass(box, 5.0);
    EXPECT_EQ(p.mass, 5.0);
    EXPECT_EQ(p.centerOfMass, box.centerOfMass);
    expectMatrixNear(p.inertia, Mat3(boxMoments(size, 5.0).asDiagonal()), 1e-14);

    // Nothing to scale from zero: stays massless, no NaN.
    const MassProperties none = withMass(MassProperties{}, 5.0);
    expectAllFinite(none);
    EXPECT_EQ(none.mass, 0.0);
}

// --- Principal frame ----------------------------------------------------------------------

void expectValidFrame(const Mat3& inertia, const PrincipalFrame& frame) {
    EXPECT_NEAR(frame.rotation.norm(), 1.0, 1e-15);
    const Mat3 r = frame.rotation.toRotationMatrix();
    EXPECT_NEAR(r.determinant(), 1.0, 1e-12);
    EXPECT_LE(frame.moments.x(), frame.moments.y());
    EXPECT_LE(frame.moments.y(), frame.moments.z());
    expectMatrixNear(r * frame.moments.asDiagonal() * r.transpose(), inertia,
                     1e-12 * inertia.norm());
}

TEST(MassPropertiesTest, PrincipalFrameOfDiagonalTensor) {
    for (const Vec3& d :
         {Vec3(3, 1, 2), Vec3(1, 2, 3), Vec3(2, 2, 2), Vec3(1, 1, 3), Vec3(3, 2, 1)}) {
        const Mat3 inertia = d.asDiagonal();
        const PrincipalFrame frame = principalFrame(inertia);
        expectValidFrame(inertia, frame);
        Vec3 sorted = d;
        std::sort(sorted.begin(), sorted.end());
        EXPECT_LE((frame.moments - sorted).norm(), 1e-15);
        // A signed permutation: each column is a coordinate axis (unless moments repeat).
        if (sorted.x() < sorted.y() && sorted.y() < sorted.z()) {
            const Mat3 r = frame.rotation.toRotationMatrix();
            EXPECT_NEAR(r.cwiseAbs().colwise().maxCoeff().sum(), 3.0, 1e-12);
        }
    }
}

TEST(MassPropertiesTest, PrincipalFrameOfRandomSymmetricPositiveTensor) {
    std::mt19937 random(12345);
    std::uniform_real_distribution<double> uniform(-1.0, 1.0);
    for (int trial = 0; trial < 50; ++trial) {
        Mat3 b;
        for (double& x : b.reshaped())
            x = uniform(random);
        const Mat3 inertia = b * b.transpose() + 0.01 * Mat3::Identity();
        expectValidFrame(inertia, principalFrame(inertia));
    }
}

}  // namespace
}  // namespace substep
