#include "mesh_import.h"

#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <utility>
#include <vector>

#include "errors.h"
#include "gltf_accessors.h"
#include "gltf_vertex_attributes.h"
#include "scene_triangles.h"

namespace gridrt {
namespace {

namespace fs = std::filesystem;

std::string lowerExtension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

glm::dmat4 toGlm(const aiMatrix4x4& m) {
  glm::dmat4 out;  // out[column][row]; assimp's a1..a4 is the first row
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) out[c][r] = m[r][c];
  return out;
}

glm::vec3 colorOf(const aiMaterial& m, const char* key, unsigned type, unsigned index,
                  glm::vec3 fallback) {
  aiColor3D c;
  if (m.Get(key, type, index, c) != AI_SUCCESS) return fallback;
  return {c.r, c.g, c.b};
}

// Kd, Ks, Ns and Ke onto gridrt's material terms (mesh_import.h says how).
Material convertMaterial(const aiMaterial& m, size_t index) {
  const aiString name = m.GetName();
  if (std::string(name.C_Str()) == AI_DEFAULT_MATERIAL_NAME) return Material{};
  Material out;
  out.name = name.length > 0 ? name.C_Str() : "material " + std::to_string(index);
  out.base_color = colorOf(m, AI_MATKEY_COLOR_DIFFUSE, out.base_color);
  out.emissive = colorOf(m, AI_MATKEY_COLOR_EMISSIVE, out.emissive);
  const glm::vec3 specular = colorOf(m, AI_MATKEY_COLOR_SPECULAR, glm::vec3(0.0f));
  float shininess = 0.0f;
  if (m.Get(AI_MATKEY_SHININESS, shininess) != AI_SUCCESS) shininess = 0.0f;
  out.metallic = 0.0f;
  const bool highlight = std::max({specular.r, specular.g, specular.b}) > 0.0f && shininess > 0.0f;
  // Phong exponent n = 2/α² − 2 (the renderer's mapping), so α² = 2/(n + 2), roughness = √α.
  out.roughness = highlight ? float(std::pow(2.0 / (double(shininess) + 2.0), 0.25)) : 1.0f;
  return out;
}

class MeshImporter {
 public:
  MeshImporter(const aiScene& file, const std::string& label) : file_(file), label_(label) {}

  Scene build() {
    for (unsigned i = 0; i < file_.mNumMaterials; ++i)
      scene_.materials.push_back(convertMaterial(*file_.mMaterials[i], i));
    traverse();
    if (scene_.positions.empty()) gltf::fail(label_, "the scene has no triangles");
    finishNormals(any_normals_, scene_);
    gltf::finishVertexAttributes(scene_);
    warnAboutIgnored();
    addDropWarnings(scene_);
    for (std::string& w : scene_.warnings) w = gltf::oneLine(w);  // names may hold newlines
    return std::move(scene_);
  }

 private:
  // Depth-first, a node's meshes before its children, on an explicit stack.
  void traverse() {
    std::vector<std::pair<const aiNode*, glm::dmat4>> stack;
    if (file_.mRootNode) stack.push_back({file_.mRootNode, glm::dmat4(1.0)});
    while (!stack.empty()) {
      const auto [node, parent] = stack.back();
      stack.pop_back();
      const glm::dmat4 world = parent * toGlm(node->mTransformation);
      for (unsigned i = 0; i < node->mNumMeshes; ++i) addMesh(node->mMeshes[i], world);
      for (unsigned c = node->mNumChildren; c-- > 0;) stack.push_back({node->mChildren[c], world});
    }
  }

  void addMesh(unsigned index, const glm::dmat4& world) {
    if (index >= file_.mNumMeshes)
      gltf::fail(label_, "mesh " + std::to_string(index) + " does not exist");
    const aiMesh& mesh = *file_.mMeshes[index];
    const std::string where = gltf::named("mesh", index, mesh.mName.C_Str());
    // Points and lines are meshes of their own (SortByPType); polygons are triangulated.
    const unsigned others = aiPrimitiveType_POINT | aiPrimitiveType_LINE | aiPrimitiveType_POLYGON;
    if (!(mesh.mPrimitiveTypes & aiPrimitiveType_TRIANGLE) || (mesh.mPrimitiveTypes & others)) {
      ++scene_.skipped_primitives;
      return;
    }
    int material = int(mesh.mMaterialIndex);
    if (mesh.mMaterialIndex >= scene_.materials.size()) material = defaultMaterial();
    gltf::VertexAttributes attributes;
    if (mesh.HasVertexColors(0)) {
      std::vector<glm::vec4>& colors = attributes.colors.emplace(mesh.mNumVertices);
      for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
        const aiColor4D& c = mesh.mColors[0][v];
        colors[v] = {c.r, c.g, c.b, c.a};
      }
    }
    const glm::dmat3 normal_matrix = glm::transpose(glm::inverse(glm::dmat3(world)));
    const bool mirrored = glm::determinant(glm::dmat3(world)) < 0.0;
    const glm::vec4 no_tangents[3] = {};
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3)
        gltf::fail(label_, where + ": face " + std::to_string(f) + " has " +
                               std::to_string(face.mNumIndices) + " vertices, not 3");
      uint32_t vertices[3];
      glm::vec3 p[3], n[3];
      for (int k = 0; k < 3; ++k) {
        vertices[k] = face.mIndices[k];
        if (vertices[k] >= mesh.mNumVertices)
          gltf::fail(label_, where + ": face " + std::to_string(f) + ": index " +
                                 std::to_string(vertices[k]) + " out of range for " +
                                 std::to_string(mesh.mNumVertices) + " vertices");
        const aiVector3D& v = mesh.mVertices[vertices[k]];
        p[k] = glm::vec3(glm::dvec3(world * glm::dvec4(v.x, v.y, v.z, 1.0)));
        n[k] = glm::vec3(0.0f);
        if (mesh.HasNormals()) {
          const aiVector3D& m = mesh.mNormals[vertices[k]];
          n[k] = unitOr(normal_matrix * glm::dvec3(m.x, m.y, m.z), glm::vec3(0.0f));
        }
      }
      if (!keepTriangle(p, scene_)) continue;
      if (mirrored)
        std::swap(p[1], p[2]), std::swap(n[1], n[2]), std::swap(vertices[1], vertices[2]);
      gltf::appendTriangleAttributes(attributes, vertices, no_tangents, scene_.material_of.size(),
                                     scene_);
      addTriangle(p, n, material, scene_);
      any_normals_ = any_normals_ || mesh.HasNormals();
    }
  }

  int defaultMaterial() {
    if (default_material_ < 0) {
      default_material_ = int(scene_.materials.size());
      scene_.materials.push_back(Material{});
    }
    return default_material_;
  }

  void warnAboutIgnored() {
    auto count = [](unsigned n, const char* what) {
      return n ? std::to_string(n) + " " + what : std::string();
    };
    std::string ignored;
    for (const std::string& part :
         {count(file_.mNumCameras, "camera(s)"), count(file_.mNumLights, "light(s)"),
          count(file_.mNumAnimations, "animation(s)"), count(file_.mNumTextures, "texture(s)")})
      if (!part.empty()) ignored += (ignored.empty() ? "" : ", ") + part;
    size_t textured = 0;
    for (unsigned i = 0; i < file_.mNumMaterials; ++i)
      for (aiTextureType type : {aiTextureType_DIFFUSE, aiTextureType_SPECULAR,
                                 aiTextureType_NORMALS, aiTextureType_EMISSIVE})
        if (file_.mMaterials[i]->GetTextureCount(type) > 0) {
          ++textured;
          break;
        }
    if (textured > 0)
      ignored +=
          (ignored.empty() ? "" : ", ") + std::to_string(textured) + " material(s)' texture maps";
    if (!ignored.empty())
      scene_.warnings.push_back("ignored: " + ignored +
                                " (only geometry and material colours are imported)");
  }

  const aiScene& file_;
  const std::string& label_;
  Scene scene_;
  bool any_normals_ = false;  // some triangle came from a mesh with normals
  int default_material_ = -1;
};

}  // namespace

bool isImportedMeshFile(const std::string& path) {
  const std::string ext = lowerExtension(path);
  if (ext.empty() || ext == ".gltf" || ext == ".glb") return false;
  return Assimp::Importer().IsExtensionSupported(ext.c_str());
}

Scene importMeshFile(const std::string& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec))
    throw SceneError(gltf::oneLine("cannot open scene '" + path + "': is a directory"));
  if (!fs::exists(path, ec))
    throw SceneError(gltf::oneLine("cannot open scene '" + path + "': No such file or directory"));
  Assimp::Importer importer;
  // Points and lines in meshes of their own (then skipped); polygons to triangles.
  const aiScene* file = importer.ReadFile(
      path, aiProcess_Triangulate | aiProcess_SortByPType | aiProcess_ValidateDataStructure);
  if (!file || (file->mFlags & AI_SCENE_FLAGS_INCOMPLETE))
    gltf::fail(path, std::string("cannot import: ") + importer.GetErrorString());
  return MeshImporter(*file, path).build();
}

}  // namespace gridrt
