// COLLADA (.dae) through assimp: every triangle of every mesh instance, with the node transforms
// applied. Points and lines are ignored; polygons are triangulated by assimp. The file's up axis is
// ignored (coordinates stay as written, as URDF tools expect); its unit scale is applied.
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <Eigen/LU>
#include <algorithm>
#include <assimp/Importer.hpp>

#include "kaboum/core/error.hpp"
#include "kaboum/io/mesh_formats.hpp"

namespace kaboum::io {

using namespace kaboum::geometry;

namespace {

using Affine = Eigen::Matrix4d;

Affine toEigen(const aiMatrix4x4& m) {
  Affine out;
  for (unsigned r = 0; r < 4; ++r) {
    for (unsigned c = 0; c < 4; ++c) out(r, c) = static_cast<double>(m[r][c]);
  }
  return out;
}

void appendNode(const aiScene& scene, const aiNode& node, const Affine& parent,
                TriangleMesh& mesh) {
  const Affine world = parent * toEigen(node.mTransformation);
  const bool mirrored = world.topLeftCorner<3, 3>().determinant() < 0.0;
  for (unsigned i = 0; i < node.mNumMeshes; ++i) {
    const aiMesh& part = *scene.mMeshes[node.mMeshes[i]];
    const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
    for (unsigned v = 0; v < part.mNumVertices; ++v) {
      const aiVector3D& p = part.mVertices[v];
      const Eigen::Vector4d local(p.x, p.y, p.z, 1.0);
      mesh.vertices.push_back((world * local).head<3>());
    }
    for (unsigned f = 0; f < part.mNumFaces; ++f) {
      const aiFace& face = part.mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines
      Triangle t{base + face.mIndices[0], base + face.mIndices[1], base + face.mIndices[2]};
      if (mirrored) std::swap(t[1], t[2]);
      mesh.triangles.push_back(t);
    }
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c) {
    appendNode(scene, *node.mChildren[c], world, mesh);
  }
}

}  // namespace

TriangleMesh readDae(const std::string& path) {
  const std::string bytes = readFileBytes(path);
  Assimp::Importer importer;
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  const aiScene* scene =
      importer.ReadFileFromMemory(bytes.data(), bytes.size(), aiProcess_Triangulate, "dae");
  if (scene == nullptr || scene->mRootNode == nullptr) {
    std::string reason = importer.GetErrorString();
    std::replace(reason.begin(), reason.end(), '\n', ' ');  // errors are one line
    throw InputError(locate(path, "cannot read COLLADA: " + reason));
  }
  TriangleMesh mesh;
  appendNode(*scene, *scene->mRootNode, Affine::Identity(), mesh);
  return mesh;
}

}  // namespace kaboum::io
