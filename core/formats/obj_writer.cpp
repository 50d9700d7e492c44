// Wavefront OBJ export (mesh_formats.hpp: write_obj) through Assimp's OBJ exporter.
//
// Assimp's exporter ("objnomtl": no .mtl file) writes one `g <mesh name>` group per mesh in
// the order given, so every object is one aiMesh named building_<id> / mesh_<id> under a node of
// that name. What it does on its own: it merges identical positions across the whole file (the
// groups then share `v` lines; read_obj gives each group its own copy back), prints 9
// significant digits (round-trip for float32, Assimp's ai_real in Debian's build: 0.5 mm at
// 5 km from the origin, which is why vertices stay scene-local) and adds one face normal per
// triangle (`vn`, `f a//n b//n c//n`). Assimp's own header comment cannot be changed, so ours
// (frame, origin, provenance) goes before it.
#include <assimp/Exporter.hpp>
#include <assimp/scene.h>
#include <cstdio>
#include <memory>

#include "core/errors.hpp"
#include "core/formats/exported_object.hpp"
#include "core/formats/mesh_formats.hpp"
#include "core/formats/obj_writer_header.hpp"
#include "core/scene_io.hpp"

namespace cullcheck::formats {
namespace {

aiMesh* assimp_mesh(const MeshObject& m, const std::string& name) {
  auto* out = new aiMesh();
  out->mName = aiString(name);
  out->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
  out->mMaterialIndex = 0;
  out->mNumVertices = static_cast<unsigned>(m.vertices.size());
  out->mVertices = new aiVector3D[m.vertices.size()];
  for (std::size_t i = 0; i < m.vertices.size(); ++i)
    out->mVertices[i] = aiVector3D(static_cast<ai_real>(m.vertices[i].x), static_cast<ai_real>(m.vertices[i].y),
                                   static_cast<ai_real>(m.vertices[i].z));
  out->mNumFaces = static_cast<unsigned>(m.triangles.size());
  out->mFaces = new aiFace[m.triangles.size()];
  for (std::size_t f = 0; f < m.triangles.size(); ++f) {
    out->mFaces[f].mNumIndices = 3;
    out->mFaces[f].mIndices = new unsigned[3]{m.triangles[f][0], m.triangles[f][1], m.triangles[f][2]};
  }
  return out;
}

std::string header(const Scene& scene) {
  char origin[128];
  std::snprintf(origin, sizeof origin, "%s %.17g %.17g\n", detail::kObjOriginComment, scene.origin.x, scene.origin.y);
  return "# cullcheck scene: " + std::to_string(scene.object_count()) + " objects (" +
         std::to_string(scene.buildings.size()) + " buildings, " + std::to_string(scene.meshes.size()) +
         " meshes); generator " + scene.provenance.generator + ", seed " + std::to_string(scene.provenance.seed) +
         ", parameters " + scene.provenance.parameters_json +
         "\n# one group per object (building_<id>, mesh_<id>); metres, z up, scene-local: world = local + origin\n" +
         origin;
}

}  // namespace

void write_obj(const Scene& scene, const std::string& path) {
  const std::vector<MeshObject> meshes = exported_meshes(scene);
  auto ai = std::make_unique<aiScene>();  // owns everything below (aiScene's destructor frees it)
  ai->mRootNode = new aiNode("cullcheck_scene");
  ai->mNumMaterials = 1;
  ai->mMaterials = new aiMaterial*[1]{new aiMaterial()};
  ai->mNumMeshes = static_cast<unsigned>(meshes.size());
  ai->mMeshes = new aiMesh*[meshes.size()];
  ai->mRootNode->mNumChildren = static_cast<unsigned>(meshes.size());
  ai->mRootNode->mChildren = new aiNode*[meshes.size()];
  for (std::size_t i = 0; i < meshes.size(); ++i) {
    const std::string name = i < scene.buildings.size() ? detail::building_name(meshes[i].id) : detail::mesh_name(meshes[i].id);
    ai->mMeshes[i] = assimp_mesh(meshes[i], name);
    auto* node = new aiNode(name);
    node->mParent = ai->mRootNode;
    node->mNumMeshes = 1;
    node->mMeshes = new unsigned[1]{static_cast<unsigned>(i)};
    ai->mRootNode->mChildren[i] = node;
  }
  Assimp::Exporter exporter;
  const aiExportDataBlob* blob = exporter.ExportToBlob(ai.get(), "objnomtl");
  if (!blob) throw InputError("file " + path, "(obj)", std::string("Assimp could not export: ") + exporter.GetErrorString());
  std::string text = header(scene);
  text.append(static_cast<const char*>(blob->data), blob->size);
  write_text_file_atomically(path, text);
}

}  // namespace cullcheck::formats
