// OBJ import on hand-written files: groups and names, the up axis, polygons triangulated, UTM-size
// coordinates, the origin comment, and bad files (each an InputError naming file and field).
#include <gtest/gtest.h>

#include <fstream>

#include "core/errors.hpp"
#include "core/formats/mesh_formats.hpp"
#include "core/formats/tests/gltf_builder.hpp"

namespace cullcheck::formats {
namespace {

using testing::scratch_path;

std::string write_obj_text(const std::string& name, const std::string& text) {
  const std::string path = scratch_path(name);
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

TEST(ObjImport, GroupsAreObjectsAndPolygonsAreTriangulated) {
  const std::string path = write_obj_text("groups.obj",
                                          "v 0 0 0\nv 4 0 0\nv 4 3 0\nv 0 3 0\nv 0 0 2\n"
                                          "o building_9\nf 1 2 3 4\n"
                                          "g Lamp\nf 1 2 5\n");
  ImportReport report;
  const Scene s = read_obj(path, {}, &report);
  ASSERT_EQ(s.meshes.size(), 2u);
  EXPECT_EQ(s.meshes[0].id, 9u);
  EXPECT_EQ(s.meshes[0].name, "building_9");
  EXPECT_EQ(s.meshes[0].triangles.size(), 2u);  // the quad, by tinyobjloader
  EXPECT_EQ(s.meshes[0].vertices.size(), 4u);   // only the vertices the group uses
  EXPECT_EQ(s.meshes[1].id, 10u);               // the next free id
  EXPECT_EQ(s.meshes[1].name, "Lamp");
  EXPECT_EQ(s.meshes[1].vertices[2], (Vec3{0, 0, 2}));
  EXPECT_EQ(report.objects, 2u);
}

TEST(ObjImport, YUpFilesAreTurnedZUp) {
  const std::string path = write_obj_text("yup.obj", "v 1 2 3\nv 4 2 3\nv 1 7 3\ng a\nf 1 2 3\n");
  const Scene z = read_obj(path);
  EXPECT_EQ(z.meshes[0].vertices[0], (Vec3{1, 2, 3}));
  const Scene y = read_obj(path, {.obj_up = UpAxis::y});
  EXPECT_EQ(y.meshes[0].vertices[0], (Vec3{1, -3, 2}));  // as glTF: (x, -z, y)
  EXPECT_EQ(y.meshes[0].vertices[2], (Vec3{1, -3, 7}));
}

// Double-precision parsing: millimetres at 5,000 km survive, then the scene is rebased.
TEST(ObjImport, FiveMillionMetresSurviveRebased) {
  const std::string path = write_obj_text("far.obj",
                                          "v 5000000.123 3000000.456 0\nv 5000010.789 3000000.456 0\n"
                                          "v 5000000.123 3000000.456 7.25\ng far\nf 1 2 3\n");
  const Scene s = read_obj(path);
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_LT(std::abs(s.meshes[0].vertices[0].x), 100.0);
  // Exact: correctly rounded parsing (tinyobjloader's own parser gives 5000000.1229999987, an
  // ulp off; read_obj uses strtod's values), then a whole-metre origin (Sterbenz).
  EXPECT_EQ(s.meshes[0].vertices[0].x + s.origin.x, 5000000.123);
  EXPECT_EQ(s.meshes[0].vertices[1].x + s.origin.x, 5000010.789);
  EXPECT_EQ(s.meshes[0].vertices[0].y + s.origin.y, 3000000.456);
  EXPECT_NEAR(s.meshes[0].vertices[1].x + s.origin.x, 5000010.789, 1e-6 * 5000010.789);
  EXPECT_EQ(s.meshes[0].vertices[2].z, 7.25);
  // Our own OBJ keeps local coordinates and gives the origin in a comment, read back.
  const std::string again = scratch_path("far_again.obj");
  write_obj(s, again);
  const Scene back = read_obj(again);
  EXPECT_EQ(back.origin, s.origin);
  EXPECT_NEAR(back.meshes[0].vertices[1].x, s.meshes[0].vertices[1].x, 1e-5);
}

std::string obj_field_of_error(const std::string& path) {
  try {
    (void)read_obj(path);
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    return e.field();
  }
  return "(accepted)";
}

TEST(ObjImport, BadFilesNameTheField) {
  EXPECT_EQ(obj_field_of_error(write_obj_text("nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n")), "line 2 (v)");
  EXPECT_EQ(obj_field_of_error(write_obj_text("inf.obj", "v 0 0 0\nv 1e999 0 0\nv 0 1 0\nf 1 2 3\n")), "line 2 (v)");
  EXPECT_EQ(obj_field_of_error(write_obj_text("short.obj", "v 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")), "line 1 (v)");
  EXPECT_EQ(obj_field_of_error(write_obj_text("index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\ng a\nf 1 2 9\n")), "f (face 1)");
  EXPECT_EQ(obj_field_of_error(write_obj_text("empty.obj", "# nothing\nv 0 0 0\n")), "(scene)");
  EXPECT_EQ(obj_field_of_error(write_obj_text("flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\ng a\nf 1 2 3\n")), "triangles");
  EXPECT_EQ(obj_field_of_error(write_obj_text("clash.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\ng mesh_1\nf 1 2 3\ng 1\nf 1 3 2\n")),
            "name");
  EXPECT_EQ(obj_field_of_error(scratch_path("missing.obj")), "(file)");
}

}  // namespace
}  // namespace cullcheck::formats
