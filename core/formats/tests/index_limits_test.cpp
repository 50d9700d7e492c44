// Mesh indices and sizes at the edge of 32 bits, in every reader: a triangle index beyond the
// vertex count, an index or count that would wrap when narrowed to uint32 or added to an offset
// (glTF accessor counts, strides and offsets; OBJ face indices, which tinyobjloader reads with
// atoi into an int), and instances merged into one object. Each bad file differs from a file the
// reader accepts by one field, and must be an InputError naming that field, never wrapped
// indices or undefined behaviour (the sanitizer build runs these tests too).
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/errors.hpp"
#include "core/formats/mesh_formats.hpp"
#include "core/formats/tests/gltf_builder.hpp"
#include "core/scene_io.hpp"

namespace cullcheck::formats {
namespace {

using nlohmann::json;
using testing::scratch_path;

std::string base64(const std::vector<unsigned char>& bytes) {
  static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::uint32_t n = (std::uint32_t{bytes[i]} << 16) | (i + 1 < bytes.size() ? std::uint32_t{bytes[i + 1]} << 8 : 0) |
                            (i + 2 < bytes.size() ? std::uint32_t{bytes[i + 2]} : 0);
    out += digits[(n >> 18) & 63];
    out += digits[(n >> 12) & 63];
    out += i + 1 < bytes.size() ? digits[(n >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? digits[n & 63] : '=';
  }
  return out;
}

// One triangle (0,0,0), (1,0,0), (0,0,1) in glTF's frame: 36 bytes of float positions, then 12
// bytes of uint32 indices (the last index given), in one embedded buffer.
json triangle_gltf(std::uint32_t last_index = 2) {
  std::vector<unsigned char> bytes(48, 0);
  const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 0, 1};
  const std::uint32_t indices[3] = {0, 1, last_index};
  std::memcpy(bytes.data(), positions, 36);  // little-endian, as the build machines are
  std::memcpy(bytes.data() + 36, indices, 12);
  return {{"asset", {{"version", "2.0"}}},
          {"scene", 0},
          {"scenes", {{{"nodes", {0}}}}},
          {"nodes", {{{"name", "n"}, {"mesh", 0}}}},
          {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}}}}}}},
          {"buffers", {{{"byteLength", 48}, {"uri", "data:application/octet-stream;base64," + base64(bytes)}}}},
          {"bufferViews",
           {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 36}}, {{"buffer", 0}, {"byteOffset", 36}, {"byteLength", 12}}}},
          {"accessors",
           {{{"bufferView", 0}, {"componentType", 5126}, {"type", "VEC3"}, {"count", 3}},
            {{"bufferView", 1}, {"componentType", 5125}, {"type", "SCALAR"}, {"count", 3}}}}};
}

std::string write_text(const std::string& name, const std::string& text) {
  const std::string path = scratch_path(name);
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// The InputError's field, or "(accepted)".
template <class Read>
std::string field_of(Read&& read) {
  try {
    read();
  } catch (const InputError& e) {
    return e.field();
  }
  return "(accepted)";
}

std::string gltf_field(const json& doc, const std::string& name) {
  const std::string path = write_text(name, doc.dump());
  return field_of([&] { (void)read_gltf(path); });
}

TEST(IndexLimits, TheGltfBaselineIsAccepted) {
  const Scene s = read_gltf(write_text("baseline.gltf", triangle_gltf().dump()));
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].triangles, (std::vector<std::array<std::uint32_t, 3>>{{0, 1, 2}}));
}

TEST(IndexLimits, GltfIndexBeyondTheVertexCountIsNamed) {
  EXPECT_EQ(gltf_field(triangle_gltf(3), "index3.gltf"), "accessors[1] (indices)[2]");
  EXPECT_EQ(gltf_field(triangle_gltf(0xFFFFFFFFu), "index_max.gltf"), "accessors[1] (indices)[2]");
}

TEST(IndexLimits, GltfCountsStridesAndOffsetsThatWouldWrapAreNamed) {
  {  // 2^32 + 3 elements: narrowed to 32 bits it would read as 3, a count that fits
    json doc = triangle_gltf();
    doc["accessors"][0]["count"] = 4294967299ull;
    EXPECT_EQ(gltf_field(doc, "count_wraps.gltf"), "accessors[0] (POSITION).count");
  }
  {  // a count within the limit whose byte span (count * 12) overruns the view
    json doc = triangle_gltf();
    doc["accessors"][0]["count"] = 150000000;
    EXPECT_EQ(gltf_field(doc, "count_overruns.gltf"), "accessors[0] (POSITION).count");
  }
  {  // an accessor offset that wraps to 8 bytes before the view's start when added
    json doc = triangle_gltf();
    doc["accessors"][1]["byteOffset"] = 18446744073709551608ull;
    EXPECT_EQ(gltf_field(doc, "accessor_offset_wraps.gltf"), "accessors[1] (indices).count");
  }
  {  // a view offset + length that wraps around 2^64 back into the buffer
    json doc = triangle_gltf();
    doc["bufferViews"][1]["byteOffset"] = 18446744073709551608ull;
    doc["bufferViews"][1]["byteLength"] = 20;
    EXPECT_EQ(gltf_field(doc, "view_offset_wraps.gltf"), "bufferViews[1].byteLength");
  }
  {  // a stride of 2^32 + 12: narrowed to 32 bits it would be the valid 12 (tinygltf refuses it)
    json doc = triangle_gltf();
    doc["bufferViews"][0]["byteStride"] = 4294967308ull;
    const std::string path = write_text("stride_wraps.gltf", doc.dump());
    try {
      (void)read_gltf(path);
      ADD_FAILURE() << "a stride of 2^32 + 12 was accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(e.field(), "(document)");
      EXPECT_NE(e.problem().find("byteStride' must be the multiple of 4 : 4294967308"), std::string::npos) << e.what();
    }
  }
  {  // a stride our reader refuses itself: below the element size
    json doc = triangle_gltf();
    doc["bufferViews"][0]["byteStride"] = 8;
    EXPECT_EQ(gltf_field(doc, "stride_short.gltf"), "bufferViews[0].byteStride");
  }
}

TEST(IndexLimits, GltfInstancesMergedIntoOneObjectOffsetTheirIndices) {
  json doc = triangle_gltf();
  doc["nodes"] = {{{"name", "a"}, {"mesh", 0}}, {{"name", "b"}, {"mesh", 0}, {"translation", {5, 0, 0}}}};
  doc["scenes"][0]["nodes"] = {0, 1};
  ImportOptions by_mesh;
  by_mesh.ids = IdSource::mesh;
  by_mesh.detect_prisms = false;
  const Scene s = read_gltf(write_text("instances.gltf", doc.dump()), by_mesh);
  ASSERT_EQ(s.meshes.size(), 1u);
  ASSERT_EQ(s.meshes[0].vertices.size(), 6u);
  EXPECT_EQ(s.meshes[0].triangles, (std::vector<std::array<std::uint32_t, 3>>{{0, 1, 2}, {3, 4, 5}}));
  EXPECT_EQ(s.meshes[0].vertices[3], (Vec3{5, 0, 0}));  // the second instance, moved 5 m along x
}

std::string obj_field(const std::string& name, const std::string& text) {
  const std::string path = write_text(name, text);
  return field_of([&] { (void)read_obj(path); });
}

TEST(IndexLimits, ObjFaceIndicesThatWouldWrapInAnIntAreNamed) {
  const std::string v = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  ASSERT_EQ(obj_field("ok.obj", v + "f 1 2 3\n"), "(accepted)");
  ASSERT_EQ(obj_field("relative.obj", v + "f -3 -2 -1\n"), "(accepted)");
  // atoi("4294967299") is 3 in an int: vertex 3, which exists; so is -4294967295 (relative 1).
  EXPECT_EQ(obj_field("wraps.obj", v + "f 1 2 4294967299\n"), "line 4 (f)");
  EXPECT_EQ(obj_field("wraps_negative.obj", v + "f 1 2 -4294967295\n"), "line 4 (f)");
  EXPECT_EQ(obj_field("wraps_texture.obj", v + "vt 0 0\nf 1/4294967297 2/1 3/1\n"), "line 5 (f)");
  EXPECT_EQ(obj_field("beyond.obj", v + "f 1 2 4\n"), "f (face 1)");
}

TEST(IndexLimits, ObjLinesEndedByALoneCarriageReturnAreScannedToo) {
  // tinyobjloader ends lines at \r as well; its number parser reads "nan" as 0.
  EXPECT_EQ(obj_field("cr.obj", "v 0 0 0\rv nan 0 0\rv 0 1 0\rf 1 2 3\r"), "line 2 (v)");
  EXPECT_EQ(obj_field("cr_face.obj", "v 0 0 0\rv 1 0 0\rv 0 1 0\rf 1 2 4294967299\r"), "line 4 (f)");
  EXPECT_EQ(obj_field("crlf.obj", "v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nf 1 2 4294967299\r\n"), "line 4 (f)");
}

TEST(IndexLimits, SceneJsonIndicesBeyondTheVertexCountOrUint32AreNamed) {
  auto problem = [](const std::string& triangle) {
    const std::string text = R"({"format":"cullcheck-scene","version":2,"buildings":[],"meshes":[{"id":5,)"
                             R"("vertices":[[0,0,0],[1,0,0],[0,1,0]],"triangles":[)" + triangle + "]}]}";
    try {
      (void)scene_from_json_text(text);
    } catch (const InputError& e) {
      return e.field() + ": " + e.problem();
    }
    return std::string("(accepted)");
  };
  EXPECT_EQ(problem("[0,1,2]"), "(accepted)");
  EXPECT_EQ(problem("[0,1,4294967295]"), "triangles[0]: index 4294967295 is out of range (3 vertices)");
  EXPECT_EQ(problem("[0,1,4294967298]"), "triangles[0]: indices must be integers in [0, 2^32)");
  EXPECT_EQ(problem("[0,1,18446744073709551618]"), "triangles[0]: indices must be integers in [0, 2^32)");
}

}  // namespace
}  // namespace cullcheck::formats
