#include "physics/mass_properties.h"

#include "physics/collision/convex_hull.h"

#include <Eigen/Eigenvalues>

namespace substep {

namespace {

constexpr double kPi = 3.14159265358979323846;

/// Below this fraction of its bounding box's volume a mesh is treated as flat (no mass).
constexpr double kMeshVolumeEpsilon = 1e-12;

}  // namespace

MassProperties sphereMassProperties(double radius, double density) {
    const double mass = density * 4.0 / 3.0 * kPi * radius * radius * radius;
    return {.mass = mass, .inertia = Mat3::Identity() * (0.4 * mass * radius * radius)};
}

MassProperties boxMassProperties(const Vec3& size, double density) {
    const double mass = density * size.x() * size.y() * size.z();
    const Vec3 sq = size.cwiseProduct(size);
    const Vec3 moments = Vec3(sq.y() + sq.z(), sq.x() + sq.z(), sq.x() + sq.y()) * (mass / 12.0);
    return {.mass = mass, .inertia = moments.asDiagonal()};
}

MassProperties capsuleMassProperties(double radius, double length, double density) {
    const double r2 = radius * radius;
    const double cylinderMass = density * kPi * r2 * length;
    const double capMass = density * 2.0 / 3.0 * kPi * r2 * radius;  // one hemisphere

    // Cylinder about its centre: axial m r²/2, transverse m (3r² + h²)/12.
    double axial = 0.5 * cylinderMass * r2;
    double transverse = cylinderMass * (3.0 * r2 + length * length) / 12.0;

    // A hemisphere about its flat face's centre has the sphere's 2/5 m r² about every axis
    // through that point (it is half a sphere, cut by a plane through the centre).
    axial += 2.0 * 0.4 * capMass * r2;
    // Transverse: move to its own centroid, 3r/8 from the face (parallel axis, subtract), then
    // out to the capsule centre at h/2 + 3r/8 (parallel axis, add); both caps alike.
    const double capCentroid = 3.0 / 8.0 * radius;
    const double capDistance = 0.5 * length + capCentroid;
    const double capOwn = 0.4 * capMass * r2 - capMass * capCentroid * capCentroid;
    transverse += 2.0 * (capOwn + capMass * capDistance * capDistance);

    return {.mass = cylinderMass + 2.0 * capMass,
            .inertia = Vec3(transverse, axial, transverse).asDiagonal()};
}

MassProperties cylinderMassProperties(double radius, double length, double density) {
    const double r2 = radius * radius;
    const double mass = density * kPi * r2 * length;
    const double axial = 0.5 * mass * r2;
    const double transverse = mass * (3.0 * r2 + length * length) / 12.0;
    return {.mass = mass, .inertia = Vec3(transverse, axial, transverse).asDiagonal()};
}

MassProperties meshMassProperties(const TriangleMesh& mesh, double density) {
    if (mesh.vertices.empty() || mesh.triangles.empty()) return {};

    // Apex of the tetrahedra: any point works for a closed mesh (Blow and Binstock use the
    // origin); the vertex mean keeps the sums small and free of cancellation for far-off meshes.
    Vec3 apex = Vec3::Zero();
    Vec3 lower = mesh.vertices.front(), upper = lower;
    for (const Vec3& v : mesh.vertices) {
        apex += v;
        lower = lower.cwiseMin(v);
        upper = upper.cwiseMax(v);
    }
    apex /= static_cast<double>(mesh.vertices.size());

    // Blow and Binstock, "How to find the inertia tensor (or other mass properties) of a 3D
    // solid body represented by a triangle mesh" (2004). Tetrahedron (apex, a, b, c) is the
    // canonical one mapped by A = [a b c] with det A = 6 × its signed volume; its covariance is
    // C = det A · A C' Aᵀ with C' = (I + 11ᵀ)/120, i.e. det A (aaᵀ + bbᵀ + ccᵀ + ssᵀ)/120 for
    // s = a + b + c. Its first moment is det A/6 · s/4. Covariances of the pieces just add.
    double det = 0.0;                // 6 × volume
    Vec3 moment = Vec3::Zero();      // 24 × first moment
    Mat3 covariance = Mat3::Zero();  // 120 × covariance about the apex
    for (const auto& triangle : mesh.triangles) {
        const Vec3 a = mesh.vertices[triangle[0]] - apex;
        const Vec3 b = mesh.vertices[triangle[1]] - apex;
        const Vec3 c = mesh.vertices[triangle[2]] - apex;
        const Vec3 s = a + b + c;
        const double d = a.dot(b.cross(c));
        det += d;
        moment += d * s;
        covariance +=
            d * (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
    }

    // A flat mesh (or an open sheet) encloses no volume; dividing by it would give NaN.
    const double extent = (upper - lower).maxCoeff();
    if (std::abs(det) / 6.0 <= kMeshVolumeEpsilon * extent * extent * extent) return {};

    // Inside-out winding makes every signed volume negative: the centroid (a ratio) is right
    // as it is, the volume and covariance change sign.
    const Vec3 centroid = moment / (4.0 * det);
    const double sign = det < 0.0 ? -1.0 : 1.0;
    const double volume = sign * det / 6.0;
    covariance *= sign / 120.0;

    // Translate the covariance to the centre of mass (C' = C - V x xᵀ for the shift by -x),
    // then I = tr(C) Id - C.
    covariance = density * (covariance - volume * centroid * centroid.transpose());
    Mat3 inertia = covariance.trace() * Mat3::Identity() - covariance;
    inertia = 0.5 * (inertia + inertia.transpose());  // exactly symmetric for the eigensolver
    return {.mass = density * volume, .centerOfMass = apex + centroid, .inertia = inertia};
}

MassProperties shapeMassProperties(const Shape& shape, double density) {
    switch (shape.type) {
        case ShapeType::Sphere:
            return sphereMassProperties(shape.radius, density);
        case ShapeType::Box:
            return boxMassProperties(shape.size, density);
        case ShapeType::Capsule:
            return capsuleMassProperties(shape.radius, shape.length, density);
        case ShapeType::Cylinder:
            return cylinderMassProperties(shape.radius, shape.length, density);
        case ShapeType::Mesh: {
            // A convex mesh collides as its hull, so it weighs as its hull too (a dent in the
            // mesh is filled); the hull is built here if the shape was made without one.
            if (!shape.convex) {
                return shape.mesh ? meshMassProperties(*shape.mesh, density) : MassProperties{};
            }
            if (shape.hull) return meshMassProperties(hullTriangleMesh(*shape.hull), density);
            if (!shape.mesh) return {};
            return meshMassProperties(hullTriangleMesh(buildConvexHull(shape.mesh->vertices)),
                                      density);
        }
        case ShapeType::Heightfield:  // static only, like the plane
        case ShapeType::Spline:
        case ShapeType::Plane:  // static only: infinite extent has no finite mass
        case ShapeType::None:
            return {};
    }
    return {};
}

MassProperties withMass(const MassProperties& properties, double mass) {
    // Nothing to scale from a massless shape (plane, flat mesh): leave it massless.
    if (properties.mass <= 0.0) return properties;
    const double scale = mass / properties.mass;
    return {.mass = mass,
            .centerOfMass = properties.centerOfMass,
            .inertia = properties.inertia * scale};
}

PrincipalFrame principalFrame(const Mat3& inertia) {
    // Eigen's solver returns eigenvalues ascending with orthonormal eigenvector columns.
    const Eigen::SelfAdjointEigenSolver<Mat3> solver(0.5 * (inertia + inertia.transpose()));
    if (solver.info() != Eigen::Success) return {.moments = inertia.diagonal()};
    Mat3 rotation = solver.eigenvectors();
    // The eigenvectors may form a reflection; negating one axis keeps I = R diag Rᵀ intact.
    if (rotation.determinant() < 0.0) rotation.col(2) = -rotation.col(2);
    return {.moments = solver.eigenvalues(), .rotation = Quat(rotation).normalized()};
}

}  // namespace substep
