// Round trips through our own files: scene -> .glb -> read_gltf and scene -> .obj -> read_obj give
// back the same ids and the same buildings (exactly when the .glb's extras give them, within
// float rounding when prisms are detected from the float32 vertices), and mesh objects stay
// meshes. Counts are pinned for fixed seeds, so a change in the generators or the formats that
// alters them shows here.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "core/errors.hpp"
#include "core/formats/mesh_formats.hpp"
#include "core/formats/tests/gltf_builder.hpp"
#include "core/scene_io.hpp"
#include "generators/city.hpp"

namespace cullcheck::formats {
namespace {

using testing::scratch_path;

Scene small_manhattan() { return generators::make_city("manhattan", 7, {{"blocks_x", 2}, {"blocks_y", 2}}); }

std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

// Same ring up to where it starts, vertex by vertex within `tol`.
bool same_ring(const std::vector<Vec2>& a, const std::vector<Vec2>& b, double tol) {
  if (a.size() != b.size()) return false;
  for (std::size_t shift = 0; shift < a.size(); ++shift) {
    bool all = true;
    for (std::size_t i = 0; i < a.size() && all; ++i) all = length(a[i] - b[(i + shift) % b.size()]) <= tol;
    if (all) return true;
  }
  return false;
}

TEST(FormatsRoundTrip, ManhattanGlbGivesTheSameBuildingsExactly) {
  const Scene scene = small_manhattan();
  ASSERT_EQ(scene.buildings.size(), 24u);  // 2 x 2 blocks of 6 lots
  ASSERT_EQ(scene.triangle_count(), 240u);
  const std::string path = scratch_path("manhattan.glb");
  write_glb(scene, path);
  const std::string bytes = file_bytes(path);
  EXPECT_EQ(bytes, glb_bytes(scene));
  EXPECT_EQ(glb_bytes(scene), glb_bytes(small_manhattan()));  // byte-deterministic
  EXPECT_EQ(bytes.compare(0, 4, "glTF"), 0);

  ImportReport report;
  const Scene back = read_gltf(path, {}, &report);
  EXPECT_EQ(report.objects, 24u);
  EXPECT_EQ(report.prisms_given, 24u);
  EXPECT_EQ(report.prisms_detected, 0u);
  EXPECT_EQ(report.meshes_kept, 0u);
  EXPECT_EQ(report.degenerate_triangles_dropped, 0u);
  EXPECT_EQ(back.ids(), scene.ids());
  ASSERT_EQ(back.buildings.size(), scene.buildings.size());
  for (const Building& b : scene.buildings) {
    const Building* c = back.find(b.id);
    ASSERT_NE(c, nullptr) << b.id;
    EXPECT_EQ(c->footprint, b.footprint) << "building " << b.id;
    EXPECT_EQ(c->height, b.height) << "building " << b.id;
  }
  EXPECT_EQ(back.provenance.generator, "manhattan");
  EXPECT_EQ(back.provenance.seed, 7u);
  EXPECT_EQ(back.provenance.parameters_json, scene.provenance.parameters_json);
  // The scene JSON of what came back is the scene JSON of what went in.
  EXPECT_EQ(scene_to_json_text(back), scene_to_json_text(scene));
}

TEST(FormatsRoundTrip, ManhattanGlbWithoutExtrasGivesTheSameBuildingsByPrismDetection) {
  const Scene scene = small_manhattan();
  const std::string path = scratch_path("manhattan_bare.glb");
  write_glb(scene, path);
  // Strip every extra with tinygltf (what a tool that drops extras would write).
  tinygltf::Model model;
  tinygltf::TinyGLTF gltf;
  std::string err, warn;
  ASSERT_TRUE(gltf.LoadBinaryFromFile(&model, &err, &warn, path)) << err;
  model.asset.extras = tinygltf::Value();
  for (tinygltf::Node& n : model.nodes) n.extras = tinygltf::Value();
  for (tinygltf::Mesh& m : model.meshes) m.extras = tinygltf::Value();
  ASSERT_TRUE(gltf.WriteGltfSceneToFile(&model, path, false, true, false, true));
  ASSERT_EQ(file_bytes(path).find("cullcheck_id"), std::string::npos);

  ImportReport report;
  const Scene back = read_gltf(path, {}, &report);
  EXPECT_EQ(report.prisms_given, 0u);
  EXPECT_EQ(report.prisms_detected, 24u);
  EXPECT_EQ(back.ids(), scene.ids());  // from the node names building_<id>
  EXPECT_EQ(back.provenance.generator, "file");
  for (const Building& b : scene.buildings) {
    const Building* c = back.find(b.id);
    ASSERT_NE(c, nullptr) << b.id;
    EXPECT_TRUE(same_ring(c->footprint, b.footprint, 1e-3)) << "building " << b.id;
    EXPECT_NEAR(c->height, b.height, 1e-3) << "building " << b.id;
  }
}

TEST(FormatsRoundTrip, ManhattanObjGivesTheSameIdsAndTrianglesWithinFloatRounding) {
  const Scene scene = small_manhattan();
  const std::string path = scratch_path("manhattan.obj");
  write_obj(scene, path);
  const std::string text = file_bytes(path);
  write_obj(small_manhattan(), path);
  EXPECT_EQ(file_bytes(path), text);  // deterministic
  EXPECT_NE(text.find("\ng building_0\n"), std::string::npos);  // one group per object, named
  EXPECT_NE(text.find("# cullcheck origin: 0 0\n"), std::string::npos);

  ImportReport report;
  const Scene meshes = read_obj(path, {.detect_prisms = false}, &report);
  EXPECT_EQ(report.objects, 24u);
  EXPECT_EQ(meshes.ids(), scene.ids());
  const std::vector<MeshObject> exported = exported_meshes(scene);
  for (const MeshObject& want : exported) {
    const MeshObject* got = meshes.find_mesh(want.id);
    ASSERT_NE(got, nullptr) << want.id;
    EXPECT_EQ(got->name, "building_" + std::to_string(want.id));
    ASSERT_EQ(got->triangles.size(), want.triangles.size()) << want.id;
    for (std::size_t t = 0; t < want.triangles.size(); ++t)
      for (int k = 0; k < 3; ++k) {
        const Vec3 a = got->vertices[got->triangles[t][k]], b = want.vertices[want.triangles[t][k]];
        const double tol = 6e-8 * std::max({1.0, std::abs(b.x), std::abs(b.y), std::abs(b.z)});  // float32 rounding
        EXPECT_NEAR(a.x, b.x, tol);
        EXPECT_NEAR(a.y, b.y, tol);
        EXPECT_NEAR(a.z, b.z, tol);
      }
  }
  // With detection (the default), every box is a building again.
  ImportReport detected;
  const Scene buildings = read_obj(path, {}, &detected);
  EXPECT_EQ(detected.prisms_detected, 24u);
  for (const Building& b : scene.buildings) {
    const Building* c = buildings.find(b.id);
    ASSERT_NE(c, nullptr);
    EXPECT_TRUE(same_ring(c->footprint, b.footprint, 1e-3)) << "building " << b.id;
  }
}

// Openings seed 1 with the defaults: 123 buildings and 19 mesh objects (7 facade walls,
// 10 arcades, 2 bridges), pinned; the meshes come back as meshes, with their names.
TEST(FormatsRoundTrip, OpeningsMeshesStayMeshes) {
  const Scene scene = generators::make_city("openings", 1, nullptr);
  ASSERT_EQ(scene.buildings.size(), 123u);
  ASSERT_EQ(scene.meshes.size(), 19u);
  std::size_t mesh_triangles = 0;
  for (const MeshObject& m : scene.meshes) mesh_triangles += m.triangles.size();
  EXPECT_EQ(mesh_triangles, 8872u);

  const std::string glb = scratch_path("openings.glb");
  write_glb(scene, glb);
  ImportReport report;
  const Scene back = read_gltf(glb, {}, &report);
  EXPECT_EQ(report.prisms_given, 123u);
  EXPECT_EQ(report.meshes_kept, 19u);
  EXPECT_EQ(back.ids(), scene.ids());
  for (const MeshObject& m : scene.meshes) {
    const MeshObject* c = back.find_mesh(m.id);
    ASSERT_NE(c, nullptr) << m.id;
    EXPECT_EQ(c->name, m.name);
    EXPECT_EQ(c->triangles, m.triangles);
    EXPECT_EQ(c->closed, m.closed);
    ASSERT_EQ(c->vertices.size(), m.vertices.size());
    for (std::size_t i = 0; i < m.vertices.size(); ++i)  // float32 vertices: 1 mm survives
      EXPECT_LT(length(c->vertices[i] - m.vertices[i]), 1e-5) << "mesh " << m.id << " vertex " << i;
  }
  for (const Building& b : scene.buildings) {  // given: exact
    const Building* c = back.find(b.id);
    ASSERT_NE(c, nullptr) << b.id;
    EXPECT_EQ(c->footprint, b.footprint);
  }

  const std::string obj = scratch_path("openings.obj");
  write_obj(scene, obj);
  ImportReport obj_report;
  const Scene from_obj = read_obj(obj, {}, &obj_report);
  EXPECT_EQ(obj_report.prisms_detected, 123u);
  EXPECT_EQ(obj_report.meshes_kept, 19u);
  EXPECT_EQ(from_obj.ids(), scene.ids());
  for (const MeshObject& m : scene.meshes) {
    const MeshObject* c = from_obj.find_mesh(m.id);
    ASSERT_NE(c, nullptr) << m.id;
    EXPECT_EQ(c->triangles.size(), m.triangles.size());
  }
}

TEST(FormatsRoundTrip, AnyFileByExtension) {
  const Scene scene = small_manhattan();
  const std::string json = scratch_path("any.json"), glb = scratch_path("any.GLB"), obj = scratch_path("any.obj");
  write_scene_file(scene, json);
  write_glb(scene, glb);
  write_obj(scene, obj);
  EXPECT_EQ(scene_to_json_text(read_scene_file_any(json)), scene_to_json_text(scene));
  EXPECT_EQ(scene_to_json_text(read_scene_file_any(glb)), scene_to_json_text(scene));
  EXPECT_EQ(read_scene_file_any(obj).ids(), scene.ids());
  try {
    (void)read_scene_file_any(scratch_path("city.fbx"));
    ADD_FAILURE() << "an unknown extension was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "(extension)");
  }
}

// A failed write leaves an existing file as it was (the temporary file cannot be made: a
// directory stands in its place, which stops root too).
TEST(FormatsRoundTrip, FailedWritesNeverTruncateExistingOutput) {
  const std::string path = scratch_path("kept.glb"), obj = scratch_path("kept.obj");
  write_glb(small_manhattan(), path);
  write_obj(small_manhattan(), obj);
  const std::string before = file_bytes(path), before_obj = file_bytes(obj);
  std::filesystem::create_directories(path + ".tmp");
  std::filesystem::create_directories(obj + ".tmp");
  const Scene other = generators::make_city("openings", 2, nullptr);
  EXPECT_THROW(write_glb(other, path), InputError);
  EXPECT_THROW(write_obj(other, obj), InputError);
  EXPECT_EQ(file_bytes(path), before);
  EXPECT_EQ(file_bytes(obj), before_obj);
  std::filesystem::remove(path + ".tmp");
  std::filesystem::remove(obj + ".tmp");
}

TEST(FormatsRoundTrip, ExportedBuildingsHaveTheirTriangleCount) {
  Building l;
  l.id = 3;
  l.height = 9;
  l.footprint = {{0, 0}, {10, 0}, {10, 2}, {2, 2}, {2, 10}, {0, 10}};
  validate_and_finish(l);
  const MeshObject m = exported_mesh(l);
  EXPECT_EQ(m.triangles.size(), l.triangle_count());
  EXPECT_EQ(m.vertices.size(), 12u);
  EXPECT_FALSE(m.closed);  // no floor
  const auto prism = as_vertical_prism(m);
  ASSERT_TRUE(prism.has_value());
  EXPECT_TRUE(same_ring(prism->footprint, l.footprint, 0.0));
  EXPECT_EQ(prism->height, 9.0);
}

// A 100 x 100 thesis testbed (10,000 buildings of 46 triangles) through a .glb: every building
// comes back as a prism given by the extras. (How long writing and reading take, up to the full
// 400 x 400: bench_formats's BM_WriteGlbThesisCity and BM_ReadGltfThesisCity.)
TEST(FormatsRoundTrip, ThesisCity100x100) {
  const Scene scene = generators::make_city("thesis", 1, {{"grid_x", 100}, {"grid_y", 100}});
  const std::string path = scratch_path("thesis.glb");
  write_glb(scene, path);
  ImportReport report;
  const Scene back = read_gltf(path, {}, &report);
  EXPECT_EQ(report.prisms_given, scene.buildings.size());
  EXPECT_EQ(back.buildings.size(), scene.buildings.size());
  EXPECT_EQ(back.ids(), scene.ids());
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace cullcheck::formats
