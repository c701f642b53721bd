#include "assimp_colour.h"

#include <assimp/material.h>
#include <assimp/scene.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "model_file_check.h"

namespace stocs::detail {
namespace {

// Vertices a baked texture may bring the mesh to: a convex object takes about 30000 (its area over
// the squared edge limit), so this leaves room for intricate ones and bounds a hostile file.
constexpr size_t kMaxBakedVertices = 5'000'000;

Rgba fromFloats(float r, float g, float b) {
  const auto byte = [](float v) {
    return static_cast<uint8_t>(std::lround(255 * std::clamp(v, 0.0f, 1.0f)));
  };
  return Rgba(byte(r), byte(g), byte(b), 255);
}

/// Bilinear texture colour at `uv` (assimp's convention: origin at the image's bottom left).
/// Coordinates outside [0, 1] repeat the texture, as renderers do by default; inside, the edge
/// pixels are not blended with the opposite edge's.
Rgba sampleTexture(const cv::Mat& bgr, const Eigen::Vector2f& uv) {
  const auto repeat = [](float t) { return t >= 0 && t <= 1 ? t : t - std::floor(t); };
  const float x = repeat(uv.x()) * bgr.cols - 0.5f, y = (1 - repeat(uv.y())) * bgr.rows - 0.5f;
  const float fx = std::floor(x), fy = std::floor(y);
  const auto pixel = [](float v, int size) { return std::clamp(static_cast<int>(v), 0, size - 1); };
  Eigen::Vector3f sum = Eigen::Vector3f::Zero();
  for (int dy = 0; dy <= 1; ++dy) {
    for (int dx = 0; dx <= 1; ++dx) {
      const float w = (dx ? x - fx : 1 - (x - fx)) * (dy ? y - fy : 1 - (y - fy));
      const cv::Vec3b& p = bgr.at<cv::Vec3b>(pixel(fy + dy, bgr.rows), pixel(fx + dx, bgr.cols));
      sum += w * Eigen::Vector3f(p[2], p[1], p[0]);
    }
  }
  return fromFloats(sum.x() / 255, sum.y() / 255, sum.z() / 255);
}

/// An embedded texture's image as BGR: compressed (a PNG or JPEG file's bytes) or raw texels.
cv::Mat decodeEmbedded(const aiTexture& texture) {
  if (texture.mHeight == 0) {
    const cv::Mat bytes(1, static_cast<int>(texture.mWidth), CV_8UC1, texture.pcData);
    return cv::imdecode(bytes, cv::IMREAD_COLOR);
  }
  const cv::Mat bgra(static_cast<int>(texture.mHeight), static_cast<int>(texture.mWidth), CV_8UC4,
                     texture.pcData);  // aiTexel: b, g, r, a
  cv::Mat bgr;
  cv::cvtColor(bgra, bgr, cv::COLOR_BGRA2BGR);
  return bgr;
}

}  // namespace

SceneColours::SceneColours(const std::string& path, const aiScene& scene)
    : path_(path), scene_(scene) {}

void SceneColours::append(const aiMesh& mesh) {
  const int texture = mesh.HasTextureCoords(0) ? textureOf(mesh.mMaterialIndex) : -1;
  const Rgba material = materialColour(mesh.mMaterialIndex);
  any_colour_ |= mesh.HasVertexColors(0) || texture >= 0 || material[3] > 0;
  for (unsigned i = 0; i < mesh.mNumVertices; ++i) {
    if (mesh.HasVertexColors(0)) {
      const aiColor4D& c = mesh.mColors[0][i];
      colours_.push_back(fromFloats(c.r, c.g, c.b));
    } else {
      colours_.push_back(material);
    }
    textures_.push_back(mesh.HasVertexColors(0) ? -1 : texture);
    const aiVector3D uv = mesh.HasTextureCoords(0) ? mesh.mTextureCoords[0][i] : aiVector3D();
    uvs_.emplace_back(uv.x, uv.y);
  }
}

int SceneColours::textureOf(unsigned material) {
  const auto known = material_texture_.find(material);
  if (known != material_texture_.end()) return known->second;
  int& index = material_texture_[material] = -1;
  if (material >= scene_.mNumMaterials) return index;
  aiString file;
  const aiMaterial& m = *scene_.mMaterials[material];
  if (m.GetTexture(aiTextureType_DIFFUSE, 0, &file) != AI_SUCCESS &&
      m.GetTexture(aiTextureType_BASE_COLOR, 0, &file) != AI_SUCCESS) {
    return index;
  }
  images_.push_back(loadTexture(file.C_Str()));
  return index = static_cast<int>(images_.size()) - 1;
}

cv::Mat SceneColours::loadTexture(const std::string& file) const {
  cv::Mat bgr;
  std::string where = "embedded texture " + file;
  if (const aiTexture* embedded = scene_.GetEmbeddedTexture(file.c_str())) {
    bgr = decodeEmbedded(*embedded);
  } else {
    std::string relative = file;
    std::replace(relative.begin(), relative.end(), '\\', '/');  // Windows exporters
    where = (std::filesystem::path(path_).parent_path() / relative).string();
    std::error_code ec;  // checked first: OpenCV warns on the console about a missing file
    if (std::filesystem::is_regular_file(where, ec)) bgr = cv::imread(where, cv::IMREAD_COLOR);
  }
  if (bgr.empty()) throw modelError(path_, fmt::format("texture {}: missing or unreadable", where));
  return bgr;
}

Rgba SceneColours::materialColour(unsigned material) const {
  if (material >= scene_.mNumMaterials) return Rgba::Zero();
  const aiMaterial& m = *scene_.mMaterials[material];
  aiString name;
  aiColor4D diffuse;
  // assimp gives every mesh of a file without materials its default one: no colour of the file.
  if (m.Get(AI_MATKEY_NAME, name) == AI_SUCCESS && name == aiString(AI_DEFAULT_MATERIAL_NAME)) {
    return Rgba::Zero();
  }
  if (m.Get(AI_MATKEY_COLOR_DIFFUSE, diffuse) != AI_SUCCESS) return Rgba::Zero();
  return fromFloats(diffuse.r, diffuse.g, diffuse.b);
}

void SceneColours::subdivide(MeshData& mesh, std::vector<Rgba>& colours,
                             std::vector<Eigen::Vector2f>& uvs, std::vector<int>& textures) const {
  const float limit = kBakeEdgeRatio * pointSetDiameter(mesh.vertices);
  std::vector<Eigen::Vector3i> triangles;
  for (const Eigen::Vector3i& t : mesh.triangles) {
    float longest = 0;
    for (int k = 0; k < 3; ++k) {
      longest = std::max(longest, (mesh.vertices[t[k]] - mesh.vertices[t[(k + 1) % 3]]).norm());
    }
    const int texture = textures[t[0]];
    if (texture < 0 || textures[t[1]] != texture || textures[t[2]] != texture ||
        !(longest > limit)) {
      triangles.push_back(t);
      continue;
    }
    // An n x n grid of triangles in the corners' barycentric coordinates, wound as `t`.
    const int n = std::min(256, static_cast<int>(std::ceil(longest / limit)));
    if (mesh.vertices.size() + (n + 1) * (n + 2) / 2 > kMaxBakedVertices) {
      throw modelError(
          path_, fmt::format("baking its texture needs more than {} vertices", kMaxBakedVertices));
    }
    const int base = static_cast<int>(mesh.vertices.size());
    const auto index = [&](int i, int j) { return base + i * (2 * n + 3 - i) / 2 + j; };
    for (int i = 0; i <= n; ++i) {
      for (int j = 0; i + j <= n; ++j) {
        const float b = static_cast<float>(i) / n, c = static_cast<float>(j) / n, a = 1 - b - c;
        mesh.vertices.push_back(a * mesh.vertices[t[0]] + b * mesh.vertices[t[1]] +
                                c * mesh.vertices[t[2]]);
        uvs.push_back(a * uvs[t[0]] + b * uvs[t[1]] + c * uvs[t[2]]);
        textures.push_back(texture);
        colours.push_back(Rgba::Zero());
      }
    }
    for (int i = 0; i < n; ++i) {
      for (int j = 0; i + j < n; ++j) {
        triangles.emplace_back(index(i, j), index(i + 1, j), index(i, j + 1));
        if (i + j + 1 < n)
          triangles.emplace_back(index(i + 1, j), index(i + 1, j + 1), index(i, j + 1));
      }
    }
  }
  mesh.triangles = std::move(triangles);
}

void SceneColours::apply(MeshData& mesh) const {
  if (!any_colour_) return;
  std::vector<Rgba> colours = colours_;
  std::vector<Eigen::Vector2f> uvs = uvs_;
  std::vector<int> textures = textures_;
  subdivide(mesh, colours, uvs, textures);
  mesh.colours.resize(mesh.vertices.size());
  for (size_t i = 0; i < mesh.vertices.size(); ++i) {
    mesh.colours[i] = textures[i] >= 0 ? sampleTexture(images_[textures[i]], uvs[i]) : colours[i];
  }
}

}  // namespace stocs::detail
