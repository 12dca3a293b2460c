#include "physics/soft/lattice.h"

#include <algorithm>
#include <cmath>

namespace substep {
namespace {

/// The six faces of an element by corner number, each counter-clockwise seen from outside:
/// −u, +u, −v, +v, −w, +w.
constexpr std::array<std::array<int, 4>, 6> kFaces = {{
    {0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6},
}};

}  // namespace

Lattice buildBoxLattice(const Vec3& size, const std::array<int, 3>& cells) {
    Lattice lattice;
    const int nx = std::max(cells[0], 1), ny = std::max(cells[1], 1), nz = std::max(cells[2], 1);
    const auto index = [&](int i, int j, int k) {
        return static_cast<uint32_t>(i + (nx + 1) * (j + (ny + 1) * k));
    };
    lattice.positions.reserve(static_cast<size_t>((nx + 1) * (ny + 1) * (nz + 1)));
    for (int k = 0; k <= nz; ++k)
        for (int j = 0; j <= ny; ++j)
            for (int i = 0; i <= nx; ++i)
                lattice.positions.emplace_back(size.x() * (double(i) / nx - 0.5),
                                               size.y() * (double(j) / ny - 0.5),
                                               size.z() * (double(k) / nz - 0.5));
    lattice.inner.assign(lattice.positions.size(), 0);
    lattice.elements.reserve(static_cast<size_t>(nx * ny * nz));
    for (int k = 0; k < nz; ++k)
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                HexElement e;
                for (int n = 0; n < 8; ++n) e[n] = index(i + (n & 1), j + ((n >> 1) & 1), k + ((n >> 2) & 1));
                lattice.elements.push_back(e);
            }
    lattice.shape.assign(lattice.elements.size(), 0);
    lattice.shapeTurn.assign(lattice.elements.size(), Quat::Identity());
    return lattice;
}

Lattice buildTyreLattice(double outerRadius, double innerRadius, double width,
                         const std::array<int, 3>& cells) {
    Lattice lattice;
    const int around = std::max(cells[0], 3), radial = std::max(cells[1], 1), across = std::max(cells[2], 1);
    // Directions (around, radial, across) = (e_θ, e_r, y) are right-handed for the point
    // (r cos θ, y, r sin θ): e_θ × e_r = y.
    // Particles of a ring stored even positions around first, then the odd ones: the cells
    // that the sweep projects side by side (two apart around, below) then have their corners
    // at consecutive particles, so the batch kernel loads them instead of gathering them
    // (element_batch.h).
    const int evens = (around + 1) / 2;
    const auto index = [&](int a, int r, int c) {
        a %= around;
        const int slot = a % 2 == 0 ? a / 2 : evens + a / 2;
        return static_cast<uint32_t>(slot + around * (r + (radial + 1) * c));
    };
    lattice.positions.resize(static_cast<size_t>(around * (radial + 1) * (across + 1)));
    lattice.inner.resize(lattice.positions.size());
    for (int c = 0; c <= across; ++c)
        for (int r = 0; r <= radial; ++r)
            for (int a = 0; a < around; ++a) {
                const double theta = 2.0 * M_PI * a / around;
                const double radius = innerRadius + (outerRadius - innerRadius) * r / radial;
                lattice.positions[index(a, r, c)] = Vec3(radius * std::cos(theta),
                                                          width * (double(c) / across - 0.5),
                                                          radius * std::sin(theta));
                lattice.inner[index(a, r, c)] = r == 0 ? 1 : 0;
            }
    // The sweep order (element_batch.h): the even cells around first, then the odd ones, each
    // across, then out, then around. A ring swept around in one direction would chain every
    // element to the one before it; cells two apart around share no particle, so a sweep in
    // this order projects whole rings of them side by side, and still carries a push from the
    // tread to the rim through the radial layers in one sweep.
    for (int parity = 0; parity < 2; ++parity)
        for (int c = 0; c < across; ++c)
            for (int r = 0; r < radial; ++r)
                for (int a = parity; a < around; a += 2) {
                    HexElement e;
                    for (int n = 0; n < 8; ++n)
                        e[n] = index(a + (n & 1), r + ((n >> 1) & 1), c + ((n >> 2) & 1));
                    lattice.elements.push_back(e);
                    // Cell a is cell 0 of its ring turned by θ_a about y: (r cos θ, r sin θ)
                    // in (x, z) goes to (r cos(θ + θ_a), r sin(θ + θ_a)), a turn by −θ_a about y.
                    lattice.shape.push_back(static_cast<uint32_t>(r + radial * c));
                    lattice.shapeTurn.emplace_back(Eigen::AngleAxisd(-2.0 * M_PI * a / around, Vec3::UnitY()));
                }
    return lattice;
}

std::vector<std::array<Vec3, 8>> restShapes(const Lattice& lattice) {
    std::vector<std::array<Vec3, 8>> shapes;
    std::vector<uint8_t> made;
    for (size_t k = 0; k < lattice.elements.size(); ++k) {
        const uint32_t s = lattice.shape[k];
        if (s >= shapes.size()) shapes.resize(s + 1), made.resize(s + 1, 0);
        if (made[s] != 0) continue;
        made[s] = 1;
        Vec3 centre = Vec3::Zero();
        for (uint32_t p : lattice.elements[k]) centre += lattice.positions[p];
        centre *= 0.125;
        const Quat back = lattice.shapeTurn[k].conjugate();
        for (int j = 0; j < 8; ++j) shapes[s][j] = back * (lattice.positions[lattice.elements[k][j]] - centre);
    }
    return shapes;
}

double hexVolume(const std::array<Vec3, 8>& x) {
    // x(u, v, w) = Σ N_n x_n, trilinear; det J is at most quadratic in each of u, v, w, so the
    // two-point Gauss rule per direction integrates it exactly.
    const double g = 0.5 / std::sqrt(3.0);
    const double points[2] = {0.5 - g, 0.5 + g};
    double volume = 0.0;
    for (double u : points)
        for (double v : points)
            for (double w : points) {
                const double su[2] = {1.0 - u, u}, sv[2] = {1.0 - v, v}, sw[2] = {1.0 - w, w};
                Vec3 du = Vec3::Zero(), dv = Vec3::Zero(), dw = Vec3::Zero();
                for (int a = 0; a < 2; ++a)
                    for (int b = 0; b < 2; ++b) {
                        du += sv[a] * sw[b] * (x[1 + 2 * a + 4 * b] - x[0 + 2 * a + 4 * b]);
                        dv += su[a] * sw[b] * (x[a + 2 + 4 * b] - x[a + 0 + 4 * b]);
                        dw += su[a] * sv[b] * (x[a + 2 * b + 4] - x[a + 2 * b]);
                    }
                volume += du.dot(dv.cross(dw)) / 8.0;
            }
    return volume;
}

std::vector<std::array<uint32_t, 4>> boundaryQuads(const std::vector<HexElement>& elements) {
    // A face shared by two elements is interior: sort all faces by their sorted corners and
    // keep those that occur once.
    struct Face {
        std::array<uint32_t, 4> key;
        std::array<uint32_t, 4> quad;
    };
    std::vector<Face> faces;
    faces.reserve(elements.size() * 6);
    for (const HexElement& e : elements)
        for (const auto& f : kFaces) {
            Face face{.key = {}, .quad = {e[f[0]], e[f[1]], e[f[2]], e[f[3]]}};
            face.key = face.quad;
            std::sort(face.key.begin(), face.key.end());
            faces.push_back(face);
        }
    std::sort(faces.begin(), faces.end(), [](const Face& a, const Face& b) { return a.key < b.key; });
    std::vector<std::array<uint32_t, 4>> quads;
    for (size_t i = 0; i < faces.size();) {
        size_t j = i + 1;
        while (j < faces.size() && faces[j].key == faces[i].key) ++j;
        if (j - i == 1) quads.push_back(faces[i].quad);
        i = j;
    }
    return quads;
}

}  // namespace substep
