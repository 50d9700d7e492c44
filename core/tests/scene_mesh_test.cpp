// Mesh objects in the scene model (core/scene.cpp) and in scene JSON version 2
// (core/scene_io.cpp): the closed flag, bounds, ids, the exact written text, round trips, errors
// that name the object and field, and rebasing of far scenes. Expected values are worked out by
// hand in the comments.
#include <gtest/gtest.h>

#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "core/scene.hpp"
#include "core/scene_io.hpp"

namespace cullcheck {
namespace {

// The unit tetrahedron (0,0,0), (1,0,0), (0,1,0), (0,0,1) moved by `at`, each face
// counter-clockwise seen from outside: bottom (0,2,1), y = 0 side (0,1,3), slanted (1,2,3),
// x = 0 side (0,3,2). Its 12 directed edges pair up: (0,2)/(2,0), (2,1)/(1,2), (1,0)/(0,1),
// (1,3)/(3,1), (3,0)/(0,3), (2,3)/(3,2): closed.
MeshObject tetrahedron(ObjectId id, Vec3 at = {}, double size = 1.0) {
  MeshObject m;
  m.id = id;
  m.vertices = {at, at + Vec3{size, 0, 0}, at + Vec3{0, size, 0}, at + Vec3{0, 0, size}};
  m.triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  return m;
}

const char* kTetrahedronJson =
    R"({"id":2,"name":"tet","vertices":[[20,0,0],[21,0,0],[20,1,0],[20,0,1]],"triangles":[[0,2,1],[0,1,3],[1,2,3],[0,3,2]]})";
const char* kBuildingJson = R"({"id":1,"height":12,"footprint":[[0,0],[10,0],[10,8],[0,8]]})";

std::string scene_text(int version, const std::string& buildings, const std::string& meshes) {
  std::string text = R"({"format":"cullcheck-scene","version":)" + std::to_string(version) + R"(,"buildings":[)" + buildings + "]";
  if (!meshes.empty()) text += R"(,"meshes":[)" + meshes + "]";
  return text + "}";
}

// --- finish_mesh and the scene's queries -------------------------------------------------------

TEST(FinishMesh, ClosedTetrahedronIsClosed) {
  MeshObject m = tetrahedron(1);
  finish_mesh(m);
  EXPECT_TRUE(m.closed);
  EXPECT_EQ(m.bounds.lo, (Vec3{0, 0, 0}));
  EXPECT_EQ(m.bounds.hi, (Vec3{1, 1, 1}));
}

TEST(FinishMesh, MissingFaceFlippedFaceOrRepeatedFaceIsOpen) {
  MeshObject missing = tetrahedron(1);
  missing.triangles.pop_back();  // without (0,3,2) edges (3,2), (2,0), (0,3) have no twin
  finish_mesh(missing);
  EXPECT_FALSE(missing.closed);
  MeshObject flipped = tetrahedron(1);
  flipped.triangles[0] = {0, 1, 2};  // now (0,1) appears twice and (1,0) not at all
  finish_mesh(flipped);
  EXPECT_FALSE(flipped.closed);
  MeshObject repeated = tetrahedron(1);
  repeated.triangles.push_back({0, 2, 1});  // (0,2) counted twice
  finish_mesh(repeated);
  EXPECT_FALSE(repeated.closed);
  MeshObject empty;
  finish_mesh(empty);
  EXPECT_FALSE(empty.closed);  // no triangle: nothing is enclosed
}

TEST(FinishMesh, BoundsCoverOnlyTheVerticesTrianglesUse) {
  MeshObject m = tetrahedron(1, {2, 3, 4});
  m.vertices.push_back({100, -100, 100});  // unused
  finish_mesh(m);
  EXPECT_TRUE(m.closed);
  EXPECT_EQ(m.bounds.lo, (Vec3{2, 3, 4}));
  EXPECT_EQ(m.bounds.hi, (Vec3{3, 4, 5}));
}

TEST(SceneWithMeshes, IdsAreSortedAcrossBuildingsAndMeshes) {
  Scene s;
  s.buildings.push_back(box_building(9, 0, 0, 10, 8, 12));
  s.buildings.push_back(box_building(3, -5, 2, -1, 4, 3));
  s.meshes.push_back(tetrahedron(5));
  s.meshes.push_back(tetrahedron(1));
  for (MeshObject& m : s.meshes) finish_mesh(m);
  EXPECT_EQ(s.ids(), (std::vector<ObjectId>{1, 3, 5, 9}));
  EXPECT_EQ(s.object_count(), 4u);
  EXPECT_FALSE(s.prisms_only());
  // Buildings: 3 * 4 - 2 = 10 triangles each; meshes 4 each: 28.
  EXPECT_EQ(s.triangle_count(), 28u);
  ASSERT_NE(s.find_mesh(5), nullptr);
  EXPECT_EQ(s.find_mesh(5)->id, 5u);
  EXPECT_EQ(s.find_mesh(9), nullptr);  // a building, not a mesh
  EXPECT_EQ(s.find(5), nullptr);       // a mesh, not a building
}

TEST(SceneWithMeshes, BoundsIncludeMeshes) {
  Scene s;
  s.buildings.push_back(box_building(9, 0, 0, 10, 8, 12));   // [0,10] x [0,8] x [0,12]
  s.buildings.push_back(box_building(3, -5, 2, -1, 4, 3));   // [-5,-1] x [2,4] x [0,3]
  s.meshes.push_back(tetrahedron(5, {20, 0, 2}, 10));        // [20,30] x [0,10] x [2,12]
  s.meshes.back().vertices[3].z = 15;                        // apex raised: z up to 15
  s.meshes.push_back(tetrahedron(1, {0, -7, 1}));            // [0,1] x [-7,-6] x [1,2]
  for (MeshObject& m : s.meshes) finish_mesh(m);
  // lo.x -5 (building 3), lo.y -7 (mesh 1), lo.z 0 (buildings); hi.x 30, hi.y 10, hi.z 15 (mesh 5).
  const Box3 b = s.bounds();
  EXPECT_EQ(b.lo, (Vec3{-5, -7, 0}));
  EXPECT_EQ(b.hi, (Vec3{30, 10, 15}));
}

// --- Scene JSON version 2: writing and round trips ----------------------------------------------

TEST(SceneJsonV2, WritesTheExactTextAndRoundTripsByteIdentically) {
  const Scene scene = scene_from_json_text(scene_text(2, kBuildingJson, kTetrahedronJson));
  ASSERT_EQ(scene.meshes.size(), 1u);
  EXPECT_TRUE(scene.meshes[0].closed);
  EXPECT_EQ(scene.meshes[0].name, "tet");
  EXPECT_EQ(scene.meshes[0].bounds.lo, (Vec3{20, 0, 0}));
  EXPECT_EQ(scene.meshes[0].bounds.hi, (Vec3{21, 1, 1}));
  // Keys sorted (nlohmann::json's objects are ordered maps), coordinates as doubles.
  const std::string expected =
      R"({"building_count":1,"buildings":[{"footprint":[[0.0,0.0],[10.0,0.0],[10.0,8.0],[0.0,8.0]],"height":12.0,"id":1}],)"
      R"("format":"cullcheck-scene","meshes":[{"id":2,"name":"tet","triangles":[[0,2,1],[0,1,3],[1,2,3],[0,3,2]],)"
      R"("vertices":[[20.0,0.0,0.0],[21.0,0.0,0.0],[20.0,1.0,0.0],[20.0,0.0,1.0]]}],)"
      R"("provenance":{"generator":"file","parameters":{},"seed":0},"version":2})"
      "\n";
  const std::string first = scene_to_json_text(scene);
  EXPECT_EQ(first, expected);
  EXPECT_EQ(scene_to_json_text(scene_from_json_text(first)), first);
}

TEST(SceneJsonV2, VersionIsOneWithoutMeshesAndTwoWithThem) {
  Scene s;
  s.buildings.push_back(box_building(1, 0, 0, 10, 8, 12));
  const nlohmann::json v1 = nlohmann::json::parse(scene_to_json_text(s));
  EXPECT_EQ(v1["version"], 1);
  EXPECT_FALSE(v1.contains("meshes"));
  s.meshes.push_back(tetrahedron(2, {20, 0, 0}));
  validate_and_finish(s.meshes.back());
  const nlohmann::json v2 = nlohmann::json::parse(scene_to_json_text(s));
  EXPECT_EQ(v2["version"], 2);
  ASSERT_TRUE(v2.contains("meshes"));
  EXPECT_EQ(v2["meshes"].size(), 1u);
  EXPECT_FALSE(v2["meshes"][0].contains("name"));  // an empty name is not written
  // A mesh-only scene (no building) is version 2 too, and reads back.
  Scene only;
  only.meshes.push_back(s.meshes.back());
  const std::string text = scene_to_json_text(only);
  EXPECT_EQ(nlohmann::json::parse(text)["version"], 2);
  EXPECT_EQ(scene_from_json_text(text).meshes.size(), 1u);
}

// --- Scene JSON version 2: bad input -----------------------------------------------------------

struct BadMesh {
  const char* name;
  std::string text, object, field;
};

TEST(SceneJsonV2, RejectsBadMeshesNamingObjectAndField) {
  const std::string tri = R"("triangles":[[0,1,2]])";
  const std::string verts = R"("vertices":[[0,0,0],[1,0,0],[0,1,0]])";
  const std::vector<BadMesh> cases = {
      {"version 1 with meshes", scene_text(1, kBuildingJson, kTetrahedronJson), "scene", "meshes"},
      {"meshes not an array", R"({"format":"cullcheck-scene","version":2,"buildings":[],"meshes":{}})", "scene", "meshes"},
      {"index out of range", scene_text(2, "", R"({"id":5,)" + verts + R"(,"triangles":[[0,1,2],[0,1,3]]})"), "mesh 5",
       "triangles[1]"},
      {"negative index", scene_text(2, "", R"({"id":5,)" + verts + R"(,"triangles":[[-1,1,2]]})"), "mesh 5", "triangles[0]"},
      {"index pair", scene_text(2, "", R"({"id":5,)" + verts + R"(,"triangles":[[0,1]]})"), "mesh 5", "triangles[0]"},
      {"string coordinate", scene_text(2, "", R"({"id":5,"vertices":[[0,0,0],[1,0,"z"],[0,1,0]],)" + tri + "}"), "mesh 5",
       "vertices[1][2]"},
      {"vertex pair", scene_text(2, "", R"({"id":5,"vertices":[[0,0,0],[1,0],[0,1,0]],)" + tri + "}"), "mesh 5",
       "vertices[1]"},
      {"vertex too high", scene_text(2, "", R"({"id":5,"vertices":[[0,0,0],[1,0,2e4],[0,1,0]],)" + tri + "}"), "mesh 5",
       "vertices[1]"},
      {"zero-area triangle (collinear)",
       scene_text(2, "", R"({"id":5,"vertices":[[0,0,0],[1,0,0],[2,0,0],[0,1,0]],"triangles":[[0,1,3],[0,1,2]]})"), "mesh 5",
       "triangles[1]"},
      {"zero-area triangle (repeated index)", scene_text(2, "", R"({"id":5,)" + verts + R"(,"triangles":[[0,0,1]]})"),
       "mesh 5", "triangles[0]"},
      {"duplicate id across building and mesh",
       scene_text(2, R"({"id":7,"height":3,"footprint":[[0,0],[1,0],[1,1]]})", R"({"id":7,)" + verts + "," + tri + "}"),
       "mesh 7", "id"},
      {"duplicate mesh id",
       scene_text(2, "", R"({"id":8,)" + verts + "," + tri + R"(},{"id":8,)" + verts + "," + tri + "}"), "mesh 8", "id"},
      {"no triangles", scene_text(2, "", R"({"id":5,)" + verts + R"(,"triangles":[]})"), "mesh 5", "triangles"},
      {"triangles missing", scene_text(2, "", R"({"id":5,)" + verts + "}"), "mesh 5", "triangles"},
      {"id missing", scene_text(2, "", "{" + verts + "," + tri + "}"), "mesh at index 0", "id"},
      {"id negative", scene_text(2, "", R"({"id":-3,)" + verts + "," + tri + "}"), "mesh -3", "id"},
      {"name not a string", scene_text(2, "", R"({"id":5,"name":4,)" + verts + "," + tri + "}"), "mesh 5", "name"},
  };
  for (const BadMesh& c : cases) {
    try {
      (void)scene_from_json_text(c.text);
      ADD_FAILURE() << c.name << ": accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(e.object(), c.object) << c.name << ": " << e.what();
      EXPECT_EQ(e.field(), c.field) << c.name << ": " << e.what();
    }
  }
}

std::string validation_field(MeshObject m) {
  try {
    validate_and_finish(m);
  } catch (const InputError& e) {
    EXPECT_EQ(e.object(), "mesh " + std::to_string(m.id)) << e.what();
    return e.field();
  }
  return "(accepted)";
}

TEST(SceneJsonV2, NonFiniteVerticesAreRefused) {
  // JSON has no NaN (a reader would refuse the text itself); importers and generators build
  // meshes in memory, where validate_and_finish must catch it.
  MeshObject m = tetrahedron(5);
  m.vertices[1].y = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(validation_field(m), "vertices[1]");
  m = tetrahedron(5);
  m.vertices[3].z = std::numeric_limits<double>::infinity();
  EXPECT_EQ(validation_field(m), "vertices[3]");
  m = tetrahedron(5);
  m.vertices[2].x = 2e9;  // beyond 1e9 m
  EXPECT_EQ(validation_field(m), "vertices[2]");
  // In a file, 1e999 overflows a double: the document itself is refused.
  try {
    (void)scene_from_json_text(scene_text(2, "", R"({"id":5,"vertices":[[0,0,0],[1e999,0,0],[0,1,0]],"triangles":[[0,1,2]]})"));
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "(document)");
  }
}

TEST(SceneJsonV2, DegenerateTrianglesCanBeDroppedAndCounted) {
  MeshObject m = tetrahedron(5);
  m.vertices.push_back({2, 0, 0});  // 4: collinear with 0 and 1
  m.triangles.insert(m.triangles.begin() + 1, std::array<std::uint32_t, 3>{0, 1, 4});  // zero area, index 1
  m.triangles.push_back({3, 3, 2});  // zero area, repeated index
  EXPECT_EQ(validation_field(m), "triangles[1]");
  EXPECT_EQ(validate_and_finish(m, /*drop_degenerate=*/true), 2u);
  ASSERT_EQ(m.triangles.size(), 4u);
  EXPECT_EQ(m.triangles[1], (std::array<std::uint32_t, 3>{0, 1, 3}));  // the others keep their order
  EXPECT_TRUE(m.closed);  // what is left is the closed tetrahedron
  // Nothing left after dropping: an error naming the triangles.
  MeshObject flat = tetrahedron(6);
  flat.triangles = {{0, 0, 1}, {2, 2, 2}};
  try {
    (void)validate_and_finish(flat, true);
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.object(), "mesh 6");
    EXPECT_EQ(e.field(), "triangles");
  }
}

// --- Rebasing far scenes -----------------------------------------------------------------------

TEST(SceneJsonV2, RebasingMovesMeshVerticesWithTheBuildings) {
  // Building [5000000, 5000010] x [5000000, 5000008]; mesh over [5000020, 5000030] x
  // [5000000, 5000010] x [0, 5]. Plan bounds [5000000, 5000030] x [5000000, 5000010], centre
  // (5000015, 5000005): 5e6 m > 1e5 m, so that whole-metre point becomes the origin.
  const std::string text = scene_text(
      2, R"({"id":1,"height":12,"footprint":[[5000000,5000000],[5000010,5000000],[5000010,5000008],[5000000,5000008]]})",
      R"({"id":2,"vertices":[[5000020,5000000,0],[5000030,5000000,0],[5000020,5000010,0],[5000020,5000000,5]],)"
      R"("triangles":[[0,2,1],[0,1,3],[1,2,3],[0,3,2]]})");
  const Scene s = scene_from_json_text(text);
  EXPECT_EQ(s.origin, (Vec2{5000015, 5000005}));
  ASSERT_EQ(s.buildings.size(), 1u);
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.buildings[0].footprint[0], (Vec2{-15, -5}));
  EXPECT_EQ(s.buildings[0].bounds.lo, (Vec3{-15, -5, 0}));
  EXPECT_EQ(s.buildings[0].bounds.hi, (Vec3{-5, 3, 12}));
  const MeshObject& m = s.meshes[0];
  EXPECT_EQ(m.vertices[0], (Vec3{5, -5, 0}));
  EXPECT_EQ(m.vertices[1], (Vec3{15, -5, 0}));
  EXPECT_EQ(m.vertices[2], (Vec3{5, 5, 0}));
  EXPECT_EQ(m.vertices[3], (Vec3{5, -5, 5}));  // z is not moved
  EXPECT_EQ(m.bounds.lo, (Vec3{5, -5, 0}));
  EXPECT_EQ(m.bounds.hi, (Vec3{15, 5, 5}));
  EXPECT_TRUE(m.closed);
  EXPECT_EQ(s.bounds().lo, (Vec3{-15, -5, 0}));
  EXPECT_EQ(s.bounds().hi, (Vec3{15, 5, 12}));
  // Written back in world coordinates, exactly.
  const std::string written = scene_to_json_text(s);
  const nlohmann::json doc = nlohmann::json::parse(written);
  EXPECT_FALSE(doc.contains("origin"));
  EXPECT_EQ(doc["meshes"][0]["vertices"][1], (nlohmann::json{5000030.0, 5000000.0, 0.0}));
  EXPECT_EQ(doc["buildings"][0]["footprint"][2], (nlohmann::json{5000010.0, 5000008.0}));
  EXPECT_EQ(scene_to_json_text(scene_from_json_text(written)), written);
}

TEST(SceneJsonV2, NearScenesAreNotRebased) {
  // Plan bounds [20, 21] x [0, 1]: far below 1e5 m, so no origin is set.
  const Scene s = scene_from_json_text(scene_text(2, "", kTetrahedronJson));
  EXPECT_EQ(s.origin, (Vec2{0, 0}));
  EXPECT_EQ(s.meshes[0].vertices[1], (Vec3{21, 0, 0}));
}

}  // namespace
}  // namespace cullcheck
