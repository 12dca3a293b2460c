#include "scene/mesh_import.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <array>
#include <cstring>
#include <system_error>
#include <unordered_map>

namespace substep {

namespace {

/// Exact position key: the bit patterns of the three coordinates (+0.0 folds -0 into 0).
struct PositionKey {
    std::array<uint64_t, 3> bits;
    bool operator==(const PositionKey&) const = default;
};

PositionKey keyOf(const Vec3& p) {
    PositionKey key;
    for (int i = 0; i < 3; ++i) {
        const double value = p[i] + 0.0;
        std::memcpy(&key.bits[i], &value, sizeof(value));
    }
    return key;
}

/// The scene file's own cap (scene_loader.cpp), for the files it names.
constexpr std::uintmax_t kMaxMeshFileBytes = std::uintmax_t{256} << 20;

struct PositionHash {
    std::size_t operator()(const PositionKey& k) const {
        uint64_t h = 1469598103934665603ull;
        for (uint64_t b : k.bits)
            h = (h ^ b) * 1099511628211ull;
        return static_cast<std::size_t>(h ^ (h >> 29));
    }
};

}  // namespace

MeshImport importTriangleMesh(const std::filesystem::path& file, const Vec3& scale) {
    MeshImport result;
    std::error_code error;
    if (!std::filesystem::exists(file, error)) {
        result.error = "cannot read mesh file " + file.string() + ": no such file";
        return result;
    }
    if (std::filesystem::is_directory(file, error)) {
        result.error = "cannot read mesh file " + file.string() + ": is a directory";
        return result;
    }
    // assimp opens the file itself and would block on a FIFO or read a device without end.
    if (!std::filesystem::is_regular_file(file, error)) {
        result.error = "cannot read mesh file " + file.string() +
                       ": not a regular file (a device, FIFO or socket)";
        return result;
    }
    if (std::filesystem::file_size(file, error) > kMaxMeshFileBytes) {
        result.error = "cannot read mesh file " + file.string() + ": larger than 256 MiB";
        return result;
    }

    Assimp::Importer importer;
    // Points and lines carry no surface: let the importer drop them.
    importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE,
                                aiPrimitiveType_POINT | aiPrimitiveType_LINE);
    const aiScene* scene = importer.ReadFile(
        file.string(), aiProcess_Triangulate | aiProcess_PreTransformVertices |
                           aiProcess_SortByPType | aiProcess_JoinIdenticalVertices);
    if (!scene) {
        // A file that parses but holds no faces is reported by assimp as having no meshes.
        const std::string why = importer.GetErrorString();
        result.error = why.find("No output meshes") != std::string::npos ||
                               why.find("no meshes") != std::string::npos
                           ? "mesh file " + file.string() + " contains no triangles"
                           : "cannot read mesh file " + file.string() + ": " + why;
        return result;
    }

    // Join by position alone, across all of the file's meshes.
    std::unordered_map<PositionKey, int, PositionHash> indexOf;
    TriangleMesh& mesh = result.mesh;
    for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
        const aiMesh* part = scene->mMeshes[m];
        std::vector<int> remap(part->mNumVertices);
        for (unsigned v = 0; v < part->mNumVertices; ++v) {
            const aiVector3D& a = part->mVertices[v];
            const Vec3 p = Vec3(a.x, a.y, a.z).cwiseProduct(scale);
            if (!p.allFinite()) {
                result.error = "mesh file " + file.string() + ": vertex " + std::to_string(v) +
                               " of mesh " + std::to_string(m) + " is not finite";
                return result;
            }
            const auto [it, added] =
                indexOf.emplace(keyOf(p), static_cast<int>(mesh.vertices.size()));
            if (added) mesh.vertices.push_back(p);
            remap[v] = it->second;
        }
        for (unsigned f = 0; f < part->mNumFaces; ++f) {
            const aiFace& face = part->mFaces[f];
            if (face.mNumIndices != 3) continue;
            const std::array<int, 3> t = {remap[face.mIndices[0]], remap[face.mIndices[1]],
                                          remap[face.mIndices[2]]};
            if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) continue;  // collapsed
            mesh.triangles.push_back(t);
        }
    }
    if (mesh.triangles.empty()) {
        result.error = "mesh file " + file.string() + " contains no triangles";
        mesh = {};
    }
    return result;
}

}  // namespace substep
