// glTF import on hand-built files: node transforms (TRS and matrix, nested) composed in double
// precision and turned z up, coordinates pinned to values computed by hand; node against mesh
// ids; the id rules; strips and fans; far-from-origin coordinates; bad files, each an InputError
// that names the file and the field.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "core/errors.hpp"
#include "core/formats/mesh_formats.hpp"
#include "core/formats/tests/gltf_builder.hpp"

namespace cullcheck::formats {
namespace {

using testing::GltfBuilder;
using testing::scratch_path;

// A right triangle in glTF's own frame: (0,0,0), (1,0,0), (0,0,1).
int triangle_mesh(GltfBuilder& g, const std::string& name) {
  const int positions = g.positions({{0, 0, 0}, {1, 0, 0}, {0, 0, 1}});
  return g.mesh(name, positions, g.indices({0, 1, 2}));
}

void expect_vertex(const MeshObject& m, std::size_t i, Vec3 want) {
  ASSERT_LT(i, m.vertices.size());
  EXPECT_NEAR(m.vertices[i].x, want.x, 1e-12) << m.name << " vertex " << i;
  EXPECT_NEAR(m.vertices[i].y, want.y, 1e-12) << m.name << " vertex " << i;
  EXPECT_NEAR(m.vertices[i].z, want.z, 1e-12) << m.name << " vertex " << i;
}

const MeshObject& mesh_named(const Scene& s, const std::string& name) {
  for (const MeshObject& m : s.meshes)
    if (m.name == name) return m;
  throw std::runtime_error("no mesh named " + name);
}

// Node A (TRS: translate (10, 0, 0), rotate 90 degrees about +Y, scale 2) holds B (matrix:
// translate (0, 1, 0)), which holds C (TRS: translate (0, 0, 5)). B and C draw the triangle.
// By hand, glTF frame, p -> T(R(S(p))) with R(x, y, z) = (z, y, -x):
//   B: (0,0,0) -> (0,1,0) -> (0,2,0) -> (0,2,0) -> (10,2,0)
//      (1,0,0) -> (1,1,0) -> (2,2,0) -> (0,2,-2) -> (10,2,-2)
//      (0,0,1) -> (0,1,1) -> (0,2,2) -> (2,2,0) -> (12,2,0)
//   C: first + (0,0,5): (0,1,5) -> (0,2,10) -> (10,2,0) -> (20,2,0); (1,1,5) -> (20,2,-2); (0,1,6) -> (22,2,0)
// then z up: (X, Y, Z) -> (X, -Z, Y).
TEST(GltfImport, NestedTrsAndMatrixNodesComposeInDoublePrecision) {
  GltfBuilder g;
  const int tri = triangle_mesh(g, "tri");
  const int a = g.node("A"), b = g.node("B", tri), c = g.node("C", tri);
  g.model.nodes[a].translation = {10, 0, 0};
  g.model.nodes[a].rotation = {0, std::sqrt(0.5), 0, std::sqrt(0.5)};
  g.model.nodes[a].scale = {2, 2, 2};
  g.model.nodes[b].matrix = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 1, 0, 1};
  g.model.nodes[c].translation = {0, 0, 5};
  g.model.nodes[a].children = {b};
  g.model.nodes[b].children = {c};
  g.scene({a});
  const std::string path = scratch_path("nested.gltf");
  g.write(path, false);
  const Scene s = read_gltf(path);
  ASSERT_EQ(s.meshes.size(), 2u);
  const MeshObject& mb = mesh_named(s, "B");
  expect_vertex(mb, 0, {10, 0, 2});
  expect_vertex(mb, 1, {10, 2, 2});
  expect_vertex(mb, 2, {12, 0, 2});
  const MeshObject& mc = mesh_named(s, "C");
  expect_vertex(mc, 0, {20, 0, 2});
  expect_vertex(mc, 1, {20, 2, 2});
  expect_vertex(mc, 2, {22, 0, 2});
  // Ids: no extras and names without numbers: the next free ids in file (node) order.
  EXPECT_EQ(mb.id, 0u);
  EXPECT_EQ(mc.id, 1u);
}

// glTF's +Y up is cullcheck's +z; glTF's +Z (towards the viewer) is cullcheck's -y.
TEST(GltfImport, YUpBecomesZUp) {
  GltfBuilder g;
  const int m = g.mesh("m", g.positions({{1, 2, 3}, {4, 2, 3}, {1, 7, 3}}));
  g.scene({g.node("object_4", m)});
  const std::string path = scratch_path("yup.glb");
  g.write(path);
  const Scene s = read_gltf(path);
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].id, 4u);  // from the name object_4
  EXPECT_EQ(s.meshes[0].vertices[0], (Vec3{1, -3, 2}));
  EXPECT_EQ(s.meshes[0].vertices[1], (Vec3{4, -3, 2}));
  EXPECT_EQ(s.meshes[0].vertices[2], (Vec3{1, -3, 7}));
}

TEST(GltfImport, TwoNodesInstancingOneMeshAreTwoObjectsByNodeAndOneByMesh) {
  GltfBuilder g;
  const int tri = triangle_mesh(g, "shared");
  const int n1 = g.node("left", tri), n2 = g.node("right", tri);
  g.model.nodes[n2].translation = {5, 0, 0};
  g.scene({n1, n2});
  const std::string path = scratch_path("instances.glb");
  g.write(path);
  ImportReport by_node_report, by_mesh_report;
  const Scene by_node = read_gltf(path, {.ids = IdSource::node}, &by_node_report);
  const Scene by_mesh = read_gltf(path, {.ids = IdSource::mesh}, &by_mesh_report);
  ASSERT_EQ(by_node.meshes.size(), 2u);
  EXPECT_EQ(by_node.meshes[0].name, "left");
  EXPECT_EQ(by_node.meshes[1].name, "right");
  EXPECT_EQ(by_node.meshes[1].vertices[0], (Vec3{5, 0, 0}));
  ASSERT_EQ(by_mesh.meshes.size(), 1u);
  EXPECT_EQ(by_mesh.meshes[0].name, "shared");
  EXPECT_EQ(by_mesh.meshes[0].triangles.size(), 2u);
  EXPECT_EQ(by_mesh.meshes[0].vertices.size(), 6u);
  EXPECT_EQ(by_mesh.meshes[0].vertices[3], (Vec3{5, 0, 0}));
  EXPECT_EQ(by_node_report.objects, 2u);
  EXPECT_EQ(by_mesh_report.objects, 1u);
}

TEST(GltfImport, IdsFromExtrasThenNamesThenTheNextFree) {
  GltfBuilder g;
  const int tri = triangle_mesh(g, "tri");
  std::vector<int> roots;
  for (const char* name : {"Tree", "building_7", "12", "mesh_3", "Lamp"}) roots.push_back(g.node(name, tri));
  g.model.nodes[roots[0]].extras = tinygltf::Value(tinygltf::Value::Object{{"cullcheck_id", tinygltf::Value(40)}});
  for (int k = 0; k < 5; ++k) g.model.nodes[roots[k]].translation = {10.0 * k, 0, 0};
  g.scene(roots);
  const std::string path = scratch_path("ids.glb");
  g.write(path);
  const Scene s = read_gltf(path);
  std::vector<std::pair<std::string, ObjectId>> got;
  for (const MeshObject& m : s.meshes) got.emplace_back(m.name, m.id);
  const std::vector<std::pair<std::string, ObjectId>> want = {
      {"Tree", 40}, {"building_7", 7}, {"12", 12}, {"mesh_3", 3}, {"Lamp", 41}};
  EXPECT_EQ(got, want);

  // A clash names both objects.
  g.model.nodes[roots[0]].extras = tinygltf::Value(tinygltf::Value::Object{{"cullcheck_id", tinygltf::Value(12)}});
  g.write(path);
  try {
    (void)read_gltf(path);
    ADD_FAILURE() << "a clash of ids was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("node 2 '12'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("node 0 'Tree'"), std::string::npos) << e.what();
    EXPECT_EQ(e.field(), "name");
  }
}

TEST(GltfImport, StripsFansAndLinesAreReadOrSkipped) {
  GltfBuilder g;
  // A unit square as a strip (0,1,2),(2,1,3) and as a fan (0,1,2),(0,2,3); and a line primitive.
  const int strip = g.mesh("strip", g.positions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}), -1,
                           TINYGLTF_MODE_TRIANGLE_STRIP);
  const int fan = g.mesh("fan", g.positions({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}), -1, TINYGLTF_MODE_TRIANGLE_FAN);
  tinygltf::Primitive line;
  line.attributes["POSITION"] = g.positions({{0, 0, 0}, {1, 0, 0}});
  line.mode = TINYGLTF_MODE_LINE;
  g.model.meshes[fan].primitives.push_back(line);
  g.scene({g.node("strip", strip), g.node("fan", fan)});
  const std::string path = scratch_path("modes.glb");
  g.write(path);
  ImportReport report;
  const Scene s = read_gltf(path, {}, &report);
  const MeshObject& st = mesh_named(s, "strip");
  ASSERT_EQ(st.triangles.size(), 2u);
  EXPECT_EQ(st.triangles[0], (std::array<std::uint32_t, 3>{0, 1, 2}));
  EXPECT_EQ(st.triangles[1], (std::array<std::uint32_t, 3>{1, 3, 2}));  // = (2, 1, 3): winding kept (spec 3.7.2.1)
  const MeshObject& fa = mesh_named(s, "fan");
  ASSERT_EQ(fa.triangles.size(), 2u);
  EXPECT_EQ(fa.triangles[0], (std::array<std::uint32_t, 3>{1, 2, 0}));
  EXPECT_EQ(fa.triangles[1], (std::array<std::uint32_t, 3>{2, 3, 0}));
  ASSERT_EQ(report.notes.size(), 1u);
  EXPECT_NE(report.notes[0].find("skipped (mode 1"), std::string::npos) << report.notes[0];
}

// UTM-size coordinates come through a double-precision node translation (float32 vertices could
// not hold them): composed in double, then rebased; world = local + origin to 1e-6 relative.
TEST(GltfImport, FiveMillionMetresSurviveRebased) {
  GltfBuilder g;
  const int m = g.mesh("far", g.positions({{0, 0, 0}, {10.25f, 0, 0}, {0, 5.5f, 0}}));
  const int n = g.node("far", m);
  g.model.nodes[n].translation = {5.0e6 + 0.125, 0, -3.0e6};  // glTF -Z = cullcheck +y
  g.scene({n});
  const std::string path = scratch_path("far.glb");
  g.write(path);
  const Scene s = read_gltf(path);
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_NE(s.origin.x, 0.0);
  EXPECT_LT(std::abs(s.meshes[0].vertices[0].x), 100.0);  // rebased near the origin
  const Vec3 want[3] = {{5.0e6 + 0.125, 3.0e6, 0}, {5.0e6 + 10.375, 3.0e6, 0}, {5.0e6 + 0.125, 3.0e6, 5.5}};
  for (int k = 0; k < 3; ++k) {
    const Vec3 v = s.meshes[0].vertices[k];
    EXPECT_NEAR(v.x + s.origin.x, want[k].x, 1e-6 * want[k].x);
    EXPECT_NEAR(v.y + s.origin.y, want[k].y, 1e-6 * want[k].y);
    EXPECT_NEAR(v.z, want[k].z, 1e-12);
    EXPECT_EQ(v.x + s.origin.x, want[k].x);  // in fact exact: whole-metre origin, Sterbenz
  }
  // Our own export keeps the vertices local and the origin beside them.
  const std::string again = scratch_path("far_again.glb");
  write_glb(s, again);
  const Scene back = read_gltf(again);
  EXPECT_EQ(back.origin, s.origin);
  EXPECT_EQ(back.meshes[0].vertices, s.meshes[0].vertices);
}

// ---- Bad files -------------------------------------------------------------------------------

std::string gltf_field_of_error(const std::string& path) {
  try {
    (void)read_gltf(path);
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << "the message must name the file: " << e.what();
    return e.field();
  }
  return "(accepted)";
}

void write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

TEST(GltfImport, BadFilesNameTheField) {
  {  // truncated .glb
    GltfBuilder g;
    g.scene({g.node("t", triangle_mesh(g, "t"))});
    const std::string full = scratch_path("full.glb"), cut = scratch_path("truncated.glb");
    g.write(full);
    std::ifstream in(full, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), {});
    write_bytes(cut, bytes.substr(0, bytes.size() / 2));
    EXPECT_EQ(gltf_field_of_error(cut), "glb header.length");
    write_bytes(cut, bytes.substr(0, 10));
    EXPECT_EQ(gltf_field_of_error(cut), "glb header");
  }
  {  // bad JSON
    const std::string path = scratch_path("bad.gltf");
    write_bytes(path, R"({"asset": {"version": "2.0"}, "nodes": [)");
    EXPECT_EQ(gltf_field_of_error(path), "(document)");
  }
  {  // NaN position
    GltfBuilder g;
    const float nan = std::nanf("");
    g.scene({g.node("n", g.mesh("n", g.positions({{0, 0, 0}, {nan, 0, 0}, {0, 1, 0}})))});
    const std::string path = scratch_path("nan.glb");
    g.write(path);
    EXPECT_EQ(gltf_field_of_error(path), "accessors[0] (POSITION)[1]");
  }
  {  // index out of range
    GltfBuilder g;
    const int positions = g.positions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    g.scene({g.node("i", g.mesh("i", positions, g.indices({0, 1, 5})))});
    const std::string path = scratch_path("index.glb");
    g.write(path);
    EXPECT_EQ(gltf_field_of_error(path), "accessors[1] (indices)[2]");
  }
  {  // non-float positions (quantised)
    GltfBuilder g;
    const std::uint16_t q[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const int acc = g.accessor(q, sizeof q, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_VEC3, 3);
    g.scene({g.node("q", g.mesh("q", acc))});
    const std::string path = scratch_path("quantised.glb");
    g.write(path);
    EXPECT_EQ(gltf_field_of_error(path), "accessors[0] (POSITION).componentType");
  }
  {  // accessor beyond its buffer view
    GltfBuilder g;
    const int acc = g.positions({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    g.model.accessors[acc].count = 1000;
    g.scene({g.node("a", g.mesh("a", acc))});
    const std::string path = scratch_path("overrun.glb");
    g.write(path);
    EXPECT_EQ(gltf_field_of_error(path), "accessors[0] (POSITION).count");
  }
  {  // a scene with nothing in it (by hand: tinygltf writes an empty scene as null)
    const std::string path = scratch_path("empty.gltf");
    write_bytes(path, R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"name":"nothing","nodes":[]}]})");
    EXPECT_EQ(gltf_field_of_error(path), "(scene)");
  }
  {  // a node cycle: A -> B -> A
    GltfBuilder g;
    const int tri = triangle_mesh(g, "t");
    const int a = g.node("A", tri), b = g.node("B", tri);
    g.model.nodes[a].children = {b};
    g.model.nodes[b].children = {a};
    g.scene({a});
    const std::string path = scratch_path("cycle.glb");
    g.write(path);
    EXPECT_EQ(gltf_field_of_error(path), "children[0]");
  }
  {  // a child that does not exist
    GltfBuilder g;
    const int a = g.node("A", triangle_mesh(g, "t"));
    g.model.nodes[a].children = {7};
    g.scene({a});
    const std::string path = scratch_path("orphan.glb");
    g.write(path);
    EXPECT_EQ(gltf_field_of_error(path), "children[0]");
  }
  {  // only zero-area triangles
    GltfBuilder g;
    g.scene({g.node("z", g.mesh("z", g.positions({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}})))});
    const std::string path = scratch_path("degenerate.glb");
    g.write(path);
    EXPECT_EQ(gltf_field_of_error(path), "triangles");
  }
}

}  // namespace
}  // namespace cullcheck::formats
