#include "scenes/model.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <string_view>
#include <system_error>

#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>
#include <glm/geometric.hpp>

#include "core/error.h"
#include "core/text.h"
#include "scenes/model_checks.h"
#include "scenes/q3_bsp.h"

namespace sl {

namespace fs = std::filesystem;

size_t Model::triangle_count() const {
    size_t count = 0;
    for (const ModelPart& part : parts) {
        count += part.mesh->triangles.size();
    }
    return count;
}

namespace {

glm::mat4 to_glm(const aiMatrix4x4& m) {
    glm::mat4 result;
    for (int row = 0; row < 4; ++row) {
        for (int column = 0; column < 4; ++column) {
            result[column][row] = m[row][column];  // assimp is row-major, glm column-major
        }
    }
    return result;
}

bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// One assimp mesh as ours: its triangles (assimp has triangulated every polygon), positions, and
// its normals where the file gives usable ones (computed, area-weighted, otherwise).
std::shared_ptr<const Mesh> convert(const aiMesh& in, const std::string& what) {
    Mesh mesh;
    mesh.positions.reserve(in.mNumVertices);
    for (unsigned i = 0; i < in.mNumVertices; ++i) {
        const aiVector3D& p = in.mVertices[i];
        mesh.positions.emplace_back(p.x, p.y, p.z);
    }
    mesh.triangles.reserve(in.mNumFaces);
    for (unsigned f = 0; f < in.mNumFaces; ++f) {
        const aiFace& face = in.mFaces[f];
        if (face.mNumIndices == 3) {  // points and lines were sorted out; nothing else is left
            mesh.triangles.emplace_back(face.mIndices[0], face.mIndices[1], face.mIndices[2]);
        }
    }
    if (mesh.triangles.empty()) {
        return nullptr;
    }
    validate_mesh(mesh, what);
    compute_vertex_normals(mesh);
    if (in.HasNormals()) {
        for (unsigned i = 0; i < in.mNumVertices; ++i) {
            const glm::vec3 n(in.mNormals[i].x, in.mNormals[i].y, in.mNormals[i].z);
            const float length = glm::length(n);
            if (finite(n) && length > 1e-6f) {
                mesh.normals[i] = n / length;
            }
        }
    }
    return std::make_shared<const Mesh>(std::move(mesh));
}

// Fails with assimp's reason.
[[noreturn]] void refuse(const Assimp::Importer& importer, const fs::path& path) {
    const std::string reason = importer.GetErrorString();
    fail("{}: cannot read the model ({})", path.string(),
         reason.empty() ? "assimp gave no reason" : reason);
}

// Reads and validates the file first, so that the limits of scenes/mesh.h hold before
// triangulation runs (its ear clipping is quadratic in a polygon's size), then triangulates.
const aiScene* read_checked(Assimp::Importer& importer, const fs::path& path) {
    importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE,
                                aiPrimitiveType_POINT | aiPrimitiveType_LINE);
    importer.SetPropertyBool(AI_CONFIG_PP_FD_REMOVE, true);
    importer.SetPropertyBool(AI_CONFIG_PP_FD_CHECKAREA, false);  // ours drops zero area only
    const aiScene* scene = importer.ReadFile(path.string(), aiProcess_ValidateDataStructure);
    if (!scene || !scene->mRootNode || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE)) {
        refuse(importer, path);
    }
    long long vertices = 0, triangles = 0;
    for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
        const aiMesh& mesh = *scene->mMeshes[m];
        vertices += mesh.mNumVertices;
        for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
            const long long corners = mesh.mFaces[f].mNumIndices;
            if (corners > kMaxFaceVertices) {
                fail("{}: a face of {} vertices, at most {}", path.string(), corners,
                     kMaxFaceVertices);
            }
            triangles += std::max(0LL, corners - 2);
        }
    }
    if (vertices > kMaxMeshVertices) {
        fail("{}: {} vertices, at most {}", path.string(), vertices, kMaxMeshVertices);
    }
    if (triangles > kMaxMeshTriangles) {
        fail("{}: {} triangles, at most {}", path.string(), triangles, kMaxMeshTriangles);
    }
    scene = importer.ApplyPostProcessing(
        aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_SortByPType |
        aiProcess_FindDegenerates | aiProcess_FindInvalidData | aiProcess_ValidateDataStructure);
    if (!scene || !scene->mRootNode) {
        refuse(importer, path);
    }
    return scene;
}

// The part's material name, diffuse colour and opacity, where the file gives finite ones.
void read_material(const aiMaterial& material, ModelPart& part) {
    aiString name;
    if (material.Get(AI_MATKEY_NAME, name) == AI_SUCCESS) {
        part.material = name.C_Str();
    }
    aiColor3D diffuse;
    if (material.Get(AI_MATKEY_COLOR_DIFFUSE, diffuse) == AI_SUCCESS) {
        const glm::vec3 d(diffuse.r, diffuse.g, diffuse.b);
        if (finite(d)) {
            part.diffuse = glm::clamp(d, 0.0f, 1.0f);
        }
    }
    float opacity = 1.0f;
    if (material.Get(AI_MATKEY_OPACITY, opacity) == AI_SUCCESS && std::isfinite(opacity)) {
        part.opacity = std::clamp(opacity, 0.0f, 1.0f);
    }
}

// One part per (node, mesh), depth-first over the node tree with an explicit stack (a deep
// hierarchy cannot overflow it; assimp's validation has refused cycles), named after its node
// (and its material or index where a node has several meshes), names kept unique.
std::vector<ModelPart> model_parts(const aiScene& scene,
                                   const std::vector<std::shared_ptr<const Mesh>>& meshes) {
    std::vector<ModelPart> parts;
    std::map<std::string, int> names;
    std::vector<std::pair<const aiNode*, glm::mat4>> stack{{scene.mRootNode, glm::mat4(1.0f)}};
    while (!stack.empty()) {
        const auto [node, parent] = stack.back();
        stack.pop_back();
        const glm::mat4 transform = parent * to_glm(node->mTransformation);
        for (unsigned k = 0; k < node->mNumMeshes; ++k) {
            const unsigned index = node->mMeshes[k];
            if (index >= scene.mNumMeshes || !meshes[index]) {
                continue;
            }
            const aiMesh& mesh = *scene.mMeshes[index];
            ModelPart part;
            part.mesh = meshes[index];
            part.transform = transform;
            if (mesh.mMaterialIndex < scene.mNumMaterials) {
                read_material(*scene.mMaterials[mesh.mMaterialIndex], part);
            }
            std::string name = node->mName.length > 0 ? node->mName.C_Str() : "node";
            if (node->mNumMeshes > 1) {
                name = fmt::format("{}/{}", name,
                                   part.material.empty() ? std::to_string(k) : part.material);
            }
            if (const int seen = names[name]++; seen > 0) {
                name = fmt::format("{}#{}", name, seen + 1);
            }
            part.name = printable(name);
            parts.push_back(std::move(part));
        }
        for (unsigned c = node->mNumChildren; c-- > 0;) {
            stack.emplace_back(node->mChildren[c], transform);
        }
    }
    return parts;
}

}  // namespace

Model load_model(const fs::path& path) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) {
        fail("{}: cannot open model file", path.string());
    }
    if (const std::string extension = lower_extension(path); extension == ".bsp") {
        return q3::load_model(path);  // assimp's Q3 BSP importer leaves its faces unset
    } else if (extension == ".obj") {
        check_obj_indices(path);
    } else if (extension == ".ply") {
        check_ply_header(path);
    }
    Assimp::Importer importer;
    const aiScene& scene = *read_checked(importer, path);
    std::vector<std::shared_ptr<const Mesh>> meshes(scene.mNumMeshes);
    for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
        meshes[m] = convert(*scene.mMeshes[m], fmt::format("{}: mesh {}", path.string(), m));
    }
    Model model;
    model.parts = model_parts(scene, meshes);
    if (model.parts.empty()) {
        fail("{}: the model holds no triangle", path.string());
    }
    for (const ModelPart& part : model.parts) {
        if (!std::isfinite(part.transform[0][0]) || !std::isfinite(part.transform[3][0]) ||
            !std::isfinite(part.transform[3][1]) || !std::isfinite(part.transform[3][2])) {
            fail("{}: node {} has a transform that is not finite", path.string(), quote(part.name));
        }
    }
    return model;
}

Mesh load_mesh(const fs::path& path) {
    if (lower_extension(path) == ".off") {
        return load_off(path);
    }
    return flatten(load_model(path), path.string());
}

Mesh flatten(const Model& model, const std::string& what) {
    Mesh mesh;
    for (const ModelPart& part : model.parts) {
        const auto base = uint32_t(mesh.positions.size());
        const glm::mat3 normal_matrix = glm::transpose(glm::inverse(glm::mat3(part.transform)));
        for (size_t i = 0; i < part.mesh->positions.size(); ++i) {
            mesh.positions.push_back(
                glm::vec3(part.transform * glm::vec4(part.mesh->positions[i], 1.0f)));
            mesh.normals.push_back(glm::normalize(normal_matrix * part.mesh->normals[i]));
        }
        const bool mirrored = glm::determinant(glm::mat3(part.transform)) < 0.0f;
        for (const glm::uvec3& t : part.mesh->triangles) {
            mesh.triangles.push_back(mirrored ? glm::uvec3(t.x, t.z, t.y) : t + base);
            if (mirrored) {
                mesh.triangles.back() += base;
            }
        }
        if (static_cast<long long>(mesh.positions.size()) > kMaxMeshVertices) {
            fail("{}: more than {} vertices", what, kMaxMeshVertices);
        }
    }
    validate_mesh(mesh, what);
    for (glm::vec3& n : mesh.normals) {
        if (!finite(n)) {
            n = glm::vec3(0.0f, 1.0f, 0.0f);
        }
    }
    return mesh;
}

}  // namespace sl
