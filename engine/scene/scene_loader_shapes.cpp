/// Scene files, the shape reader of the loader (scene_loader_shapes.h).

#include "scene/scene_loader_shapes.h"

#include "physics/collision/convex_mesh_shape.h"
#include "physics/collision/heightfield.h"
#include "physics/collision/mesh_collider.h"
#include "physics/collision/spline_tube.h"
#include "physics/mass_properties.h"
#include "scene/mesh_import.h"

#include <cmath>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace substep::scene_loader {

namespace {

/// `mesh {file, scale, convex}`, the file found relative to the scene file's folder.
Shape parseMeshShape(const Validator& v, const ObjectReader& obj, const Node& typeNode,
                     bool isStatic) {
    obj.allowOnly({"type", "file", "scale", "convex"});
    const Node fileNode = obj.require("file", " (a mesh file such as \"meshes/bunny.obj\")");
    const std::string file = v.string(fileNode);
    if (file.empty()) v.fail(fileNode.path, "must name a mesh file, got an empty string");
    Vec3 scale = Vec3::Ones();
    if (auto s = obj.get("scale")) {
        scale = s->value.is_array() ? v.vec3(*s, sizeUpTo(kMaxSize))
                                    : Vec3::Constant(v.number(*s, sizeUpTo(kMaxSize)));
    }
    bool convex = false;
    const auto convexNode = obj.get("convex");
    if (convexNode) convex = v.boolean(*convexNode);
    if (!convex && !isStatic) {
        v.fail(convexNode ? convexNode->path : typeNode.path,
               "a dynamic mesh must be convex (add \"convex\": true to collide and weigh as its "
               "convex hull); a non-convex mesh can only be on a static body");
    }

    const std::filesystem::path path = std::filesystem::path(v.file()).parent_path() / file;
    MeshImport imported = importTriangleMesh(path, scale);
    if (!imported.ok()) v.fail(fileNode.path, imported.error);
    auto mesh = std::make_shared<const TriangleMesh>(std::move(imported.mesh));
    try {
        return convex ? convexMeshShape(mesh) : triangleMeshShape(mesh);
    } catch (const std::invalid_argument& e) {
        v.fail(fileNode.path, "mesh file " + path.string() + ": " + e.what());
    }
}

constexpr std::size_t kMaxSplinePoints = 100000;
constexpr std::size_t kMaxHeightfieldSide = 4096;
constexpr double kMaxHeightfieldSlope = 1000;  // rise per run between neighbouring heights

/// `spline {points, radius, closed, hollow}`: a tube around a Catmull–Rom curve (static only).
Shape parseSplineShape(const Validator& v, const ObjectReader& obj, const Node& typeNode,
                       bool isStatic) {
    if (!isStatic) {
        v.fail(typeNode.path, "a spline must be on a static body (add \"static\": true)");
    }
    obj.allowOnly({"type", "points", "radius", "closed", "hollow"});
    const Node pointsNode = obj.require("points", " (control points [[x, y, z], ...])");
    if (!pointsNode.value.is_array() || pointsNode.value.size() < 2) {
        const std::string got = pointsNode.value.is_array()
                                    ? "an array of " + std::to_string(pointsNode.value.size())
                                    : describe(pointsNode.value);
        v.fail(pointsNode.path, "must be an array of at least 2 points [x, y, z], got " + got);
    }
    if (pointsNode.value.size() > kMaxSplinePoints) {
        v.fail(pointsNode.path, "has more than " + std::to_string(kMaxSplinePoints) +
                                    " points (a sanity bound against absurd values)");
    }
    std::vector<Vec3> points;
    for (std::size_t i = 0; i < pointsNode.value.size(); ++i) {
        points.push_back(
            v.vec3({pointsNode.value[i], elementPath(pointsNode.path, i)}, within(kMaxCoordinate)));
    }
    const double radius =
        v.number(obj.require("radius", " (the tube's radius)"), sizeUpTo(kMaxSize));
    bool closed = false, hollow = false;
    const auto closedNode = obj.get("closed");
    if (closedNode) closed = v.boolean(*closedNode);
    if (auto h = obj.get("hollow")) hollow = v.boolean(*h);
    if (closed) {
        // Distinct points, as the curve will see them (repeated neighbours merged).
        std::size_t distinct = 0;
        for (std::size_t i = 0; i < points.size(); ++i) {
            distinct += i == 0 || points[i] != points[i - 1];
        }
        if (distinct > 1 && points.front() == points.back()) --distinct;
        if (distinct < 3) {
            v.fail(closedNode->path, "a closed spline needs at least 3 distinct points, got " +
                                         std::to_string(distinct));
        }
    }
    return splineShape(makeSplineTube(std::move(points), radius, closed, hollow));
}

/// Neighbouring heights may differ by at most kMaxHeightfieldSlope times the cell's width.
/// Steeper, a cell is a wall thinner than anything that meets it, whose contacts launch bodies:
/// heights of ±1e6 m on 2.4 cm cells shot a box away at 3.5e7 m/s in its first frame.
void checkHeightfieldSlopes(const Validator& v, const std::string& path,
                            const std::vector<double>& heights, std::size_t columns,
                            std::size_t rows, double sizeX, double sizeZ) {
    const double cellX = sizeX / static_cast<double>(columns - 1);
    const double cellZ = sizeZ / static_cast<double>(rows - 1);
    const auto at = [&](std::size_t j, std::size_t i) {
        return elementPath(elementPath(path, j), i);
    };
    const auto check = [&](std::size_t j, std::size_t i, std::size_t nj, std::size_t ni,
                           double cell) {
        const double rise = std::abs(heights[j * columns + i] - heights[nj * columns + ni]);
        if (rise > kMaxHeightfieldSlope * cell) {
            v.fail(at(j, i), "differs by " + formatNumber(rise) + " m from " + at(nj, ni) + ", " +
                                 formatNumber(cell) + " m away: steeper than a slope of " +
                                 formatNumber(kMaxHeightfieldSlope) +
                                 " (a sanity bound against absurd values)");
        }
    };
    for (std::size_t j = 0; j < rows; ++j) {
        for (std::size_t i = 0; i < columns; ++i) {
            if (i > 0) check(j, i, j, i - 1, cellX);
            if (j > 0) check(j, i, j - 1, i, cellZ);
        }
    }
}

/// `heightfield {heights, size}`: rows of heights along z, each along x (static only).
Shape parseHeightfieldShape(const Validator& v, const ObjectReader& obj, const Node& typeNode,
                            bool isStatic) {
    if (!isStatic) {
        v.fail(typeNode.path, "a heightfield must be on a static body (add \"static\": true)");
    }
    obj.allowOnly({"type", "heights", "size"});
    const Node heightsNode = obj.require("heights", " (rows along z of heights along x)");
    const Json& rows = heightsNode.value;
    if (!rows.is_array() || rows.size() < 2) {
        const std::string got =
            rows.is_array() ? "an array of " + std::to_string(rows.size()) : describe(rows);
        v.fail(heightsNode.path, "must be an array of at least 2 rows, got " + got);
    }
    if (rows.size() > kMaxHeightfieldSide) {
        v.fail(heightsNode.path, "has more than " + std::to_string(kMaxHeightfieldSide) +
                                     " rows (a sanity bound against absurd values)");
    }
    std::vector<double> heights;
    std::size_t columns = 0;
    for (std::size_t j = 0; j < rows.size(); ++j) {
        const std::string rowPath = elementPath(heightsNode.path, j);
        const Json& row = rows[j];
        if (!row.is_array()) v.fail(rowPath, "must be an array of heights, got " + describe(row));
        if (j == 0) {
            columns = row.size();
            if (columns < 2 || columns > kMaxHeightfieldSide) {
                v.fail(rowPath, "must hold 2 to " + std::to_string(kMaxHeightfieldSide) +
                                    " heights, got " + std::to_string(columns));
            }
        } else if (row.size() != columns) {
            v.fail(rowPath, "must hold " + std::to_string(columns) + " heights like row 0, got " +
                                std::to_string(row.size()));
        }
        for (std::size_t i = 0; i < row.size(); ++i) {
            heights.push_back(v.number({row[i], elementPath(rowPath, i)}, within(kMaxCoordinate)));
        }
    }
    const auto size = v.numbers(obj.require("size", " (extents [x, z])"), 2,
                                sizeUpTo(kMaxCoordinate), "an array [x, z] of 2 numbers");
    checkHeightfieldSlopes(v, heightsNode.path, heights, columns, rows.size(), size[0], size[1]);
    return heightfieldShape(makeHeightfield(static_cast<int>(columns),
                                            static_cast<int>(rows.size()), std::move(heights),
                                            size[0], size[1]));
}

}  // namespace

double shapeVolume(const Shape& shape) {
    switch (shape.type) {
        case ShapeType::Sphere:
            return 4.0 / 3.0 * kPi * std::pow(shape.radius, 3);
        case ShapeType::Box:
            return shape.size.prod();
        case ShapeType::Capsule:
            return kPi * shape.radius * shape.radius * shape.length +
                   4.0 / 3.0 * kPi * std::pow(shape.radius, 3);
        case ShapeType::Cylinder:
            return kPi * shape.radius * shape.radius * shape.length;
        case ShapeType::Mesh:  // a closed mesh's volume (a convex one's hull)
            return shapeMassProperties(shape, 1.0).mass;
        default:
            return 0.0;
    }
}

Shape readShape(const Validator& v, const Node& node, bool isStatic) {
    const ObjectReader obj(v, node);
    const Node typeNode = obj.require("type", " (sphere, box, capsule, cylinder or plane)");
    const std::string type = v.string(typeNode);

    if (type == "mesh") return parseMeshShape(v, obj, typeNode, isStatic);
    if (type == "spline") return parseSplineShape(v, obj, typeNode, isStatic);
    if (type == "heightfield") return parseHeightfieldShape(v, obj, typeNode, isStatic);
    if (type == "sphere") {
        obj.allowOnly({"type", "radius"});
        return sphereShape(v.number(obj.require("radius"), sizeUpTo(kMaxSize)));
    }
    if (type == "box") {
        obj.allowOnly({"type", "size"});
        return boxShape(
            v.vec3(obj.require("size", " (full extents [x, y, z])"), sizeUpTo(kMaxSize)));
    }
    if (type == "capsule") {
        obj.allowOnly({"type", "radius", "length"});
        const double radius = v.number(obj.require("radius"), sizeUpTo(kMaxSize));
        const double length = v.number(obj.require("length", " (segment between the cap centres)"),
                                       nonNegativeUpTo(kMaxSize));
        return capsuleShape(radius, length);
    }
    if (type == "cylinder") {
        obj.allowOnly({"type", "radius", "length"});
        const double radius = v.number(obj.require("radius"), sizeUpTo(kMaxSize));
        const double length =
            v.number(obj.require("length", " (between the flat faces)"), sizeUpTo(kMaxSize));
        return cylinderShape(radius, length);
    }
    if (type == "plane") {
        if (!isStatic) {
            v.fail(typeNode.path, "a plane must be on a static body (add \"static\": true)");
        }
        obj.allowOnly({"type", "normal", "offset"});
        Vec3 normal = Vec3::UnitY();
        double offset = 0.0;
        if (auto n = obj.get("normal")) normal = v.direction(*n);
        if (auto o = obj.get("offset")) offset = v.number(*o, within(kMaxCoordinate));
        return planeShape(normal, offset);
    }
    v.fail(typeNode.path,
           "unknown shape type " + jsonQuoted(type) +
               " (expected sphere, box, capsule, cylinder, plane, mesh, heightfield or spline)");
}

}  // namespace substep::scene_loader
