#pragma once
/// Triangle meshes from files (OBJ, STL, PLY, glTF, ... whatever assimp reads) for mesh shapes.

#include "physics/collision/shape.h"

#include <filesystem>
#include <string>

namespace substep {

/// A loaded mesh, or why there is none.
struct MeshImport {
    TriangleMesh mesh;
    std::string error;  ///< empty on success; otherwise one line saying what is wrong

    bool ok() const { return error.empty(); }
};

/// Reads every mesh of the file (node transforms applied) into one triangle mesh: polygons
/// triangulated, points and lines dropped, vertices at the same position joined (so that a
/// closed surface stays closed for the mass properties even where the file splits vertices by
/// normal or texture coordinate), triangles that collapse to an edge or a point dropped, then
/// every vertex multiplied componentwise by `scale`. An unreadable file, a file without
/// triangles or with non-finite coordinates gives an error.
MeshImport importTriangleMesh(const std::filesystem::path& file, const Vec3& scale = Vec3::Ones());

}  // namespace substep
