#pragma once
// The colour of the meshes assimp reads (assimp_model.cpp): a mesh's vertex colours, else its
// material's diffuse texture, baked into vertex colours, else the material's diffuse colour.
// Textures are baked on a finer mesh: triangles with an edge longer than kBakeEdgeRatio of the
// model's diameter are subdivided, then each vertex takes the texture's colour at its texture
// coordinates. Only src/io includes assimp's headers.

#include <Eigen/Core>
#include <map>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

#include "stocs/geometry/mesh.h"

struct aiMesh;
struct aiScene;

namespace stocs::detail {

/// Longest triangle edge a baked texture is sampled across, as a fraction of the diameter.
constexpr float kBakeEdgeRatio = 0.01f;

/// Collects where each vertex of the merged mesh takes its colour from, mesh by mesh, then sets
/// the merged mesh's colours.
class SceneColours {
 public:
  /// `path`: the model file (textures are relative to its folder).
  SceneColours(const std::string& path, const aiScene& scene);

  /// The colour sources of `mesh`'s vertices, appended after the previous meshes'.
  void append(const aiMesh& mesh);
  /// Subdivides `mesh`'s textured triangles and sets its colours; leaves them empty when no mesh
  /// of the file has colour. Throws InputError naming a texture that cannot be read.
  void apply(MeshData& mesh) const;

 private:
  /// Index into images_ of `material`'s diffuse texture (loaded on first use), or -1.
  int textureOf(unsigned material);
  cv::Mat loadTexture(const std::string& file) const;
  /// The material's diffuse colour, alpha 0 for none (assimp's default material).
  Rgba materialColour(unsigned material) const;
  /// `mesh` with its textured triangles subdivided (new vertices appended, with their uv and
  /// texture), and the vertices' colour sources to match.
  void subdivide(MeshData& mesh, std::vector<Rgba>& colours, std::vector<Eigen::Vector2f>& uvs,
                 std::vector<int>& textures) const;

  std::string path_;
  const aiScene& scene_;
  bool any_colour_ = false;
  std::vector<Rgba> colours_;         ///< vertex or material colour; alpha 0: none
  std::vector<Eigen::Vector2f> uvs_;  ///< texture coordinates of textured vertices
  std::vector<int> textures_;         ///< index into images_, -1: not textured
  std::vector<cv::Mat> images_;       ///< BGR 8-bit textures
  std::map<unsigned, int> material_texture_;
};

}  // namespace stocs::detail
