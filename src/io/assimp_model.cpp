#include "assimp_model.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <fmt/format.h>
#include <assimp/Importer.hpp>

#include <algorithm>
#include <cctype>
#include <limits>
#include <utility>
#include <vector>

#include "assimp_colour.h"
#include "model_file_check.h"
#include "stocs/util/error.h"

namespace stocs::detail {
namespace {

// Far above any graspable object's model, and below the int range of triangle indices.
constexpr uint64_t kMaxVertices = 100'000'000;

/// The root's transform without its rotation, as rviz (1.14.19, Debian's; rviz pull request 1689)
/// loads meshes: assimp's COLLADA reader turns Z_UP files to Y-up in the root, which a robot's
/// frames must not see, while the root's scale carries the file's <unit>.
aiMatrix4x4 rootWithoutRotation(const aiNode& root) {
  aiVector3D scaling, position;
  aiQuaternion rotation;
  root.mTransformation.Decompose(scaling, rotation, position);
  return aiMatrix4x4(scaling, aiQuaternion(), position);
}

/// Appends `mesh`'s vertices placed by `transform`, and its triangles.
void appendMesh(const std::string& path, const aiMesh& mesh, const aiMatrix4x4& transform,
                MeshData& out) {
  if (out.vertices.size() + mesh.mNumVertices > kMaxVertices) {
    throw modelError(path, fmt::format("more than {} vertices", kMaxVertices));
  }
  const int base = static_cast<int>(out.vertices.size());
  for (unsigned i = 0; i < mesh.mNumVertices; ++i) {
    const aiVector3D p = transform * mesh.mVertices[i];
    out.vertices.emplace_back(p.x, p.y, p.z);
  }
  for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
    const aiFace& face = mesh.mFaces[f];
    if (face.mNumIndices != 3) continue;  // a point or a line: no surface
    for (unsigned k = 0; k < 3; ++k) {
      if (face.mIndices[k] >= mesh.mNumVertices) {
        throw modelError(path,
                         fmt::format("face {} of mesh '{}' refers to vertex {} of {}", f,
                                     mesh.mName.C_Str(), face.mIndices[k], mesh.mNumVertices));
      }
    }
    out.triangles.emplace_back(base + static_cast<int>(face.mIndices[0]),
                               base + static_cast<int>(face.mIndices[1]),
                               base + static_cast<int>(face.mIndices[2]));
  }
}

/// Every node's meshes, depth first without recursion (a file may nest nodes deeply), and their
/// colour (assimp_colour.h).
MeshData mergeNodes(const std::string& path, const aiScene& scene) {
  MeshData out;
  SceneColours colours(path, scene);
  std::vector<std::pair<const aiNode*, aiMatrix4x4>> pending = {
      {scene.mRootNode, rootWithoutRotation(*scene.mRootNode)}};
  while (!pending.empty()) {
    const auto [node, transform] = pending.back();
    pending.pop_back();
    for (unsigned i = 0; i < node->mNumMeshes; ++i) {
      if (node->mMeshes[i] >= scene.mNumMeshes) {
        throw modelError(path, fmt::format("node '{}' refers to mesh {} of {}", node->mName.C_Str(),
                                           node->mMeshes[i], scene.mNumMeshes));
      }
      appendMesh(path, *scene.mMeshes[node->mMeshes[i]], transform, out);
      colours.append(*scene.mMeshes[node->mMeshes[i]]);
    }
    for (unsigned c = 0; c < node->mNumChildren; ++c) {
      pending.emplace_back(node->mChildren[c], transform * node->mChildren[c]->mTransformation);
    }
  }
  colours.apply(out);
  return out;
}

std::string formatName(const std::string& ext) {
  std::string name = ext.substr(1);
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  return name;
}

}  // namespace

bool isAssimpFormat(const std::string& ext) {
  static const char* const kFormats[] = {".obj", ".stl", ".dae", ".gltf", ".glb"};
  return std::find(std::begin(kFormats), std::end(kFormats), ext) != std::end(kFormats);
}

MeshData readAssimpModel(const std::string& path, const std::string& ext) {
  if (ext == ".glb") checkGlbChunks(path);
  // No logger is created, so assimp's messages go to its silent default one; its errors come
  // back through GetErrorString.
  Assimp::Importer importer;
  const aiScene* scene =
      importer.ReadFile(path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                  aiProcess_ValidateDataStructure);
  if (!scene) {
    throw modelError(path, fmt::format("not a readable {} file ({})", formatName(ext),
                                       importer.GetErrorString()));
  }
  if ((scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) || !scene->mRootNode) {
    throw modelError(path, fmt::format("{} file holds no complete mesh", formatName(ext)));
  }
  return mergeNodes(path, *scene);
}

}  // namespace stocs::detail
