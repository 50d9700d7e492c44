// Wavefront OBJ import (mesh_formats.hpp: read_obj), through tinyobjloader's double-precision
// build (tinyobjloader::tinyobjloader_double), so UTM-size coordinates keep their millimetres.
//
// tinyobjloader reads a number it cannot parse ("nan", "1e999" overflowing) as 0 without a word,
// and its own number parser is not correctly rounded (5000000.123 comes out an ulp off); a short
// scan of the `v` lines first refuses such files instead of loading a silently different scene,
// and its strtod values (correctly rounded) replace tinyobjloader's when both saw the same
// vertices. The same scan picks up the world origin our writer puts in a comment.
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <algorithm>
#include <limits>
#include <filesystem>
#include <tiny_obj_loader.h>
#include <type_traits>
#include <unordered_map>

#include "core/errors.hpp"
#include "core/formats/import_objects.hpp"
#include "core/formats/mesh_formats.hpp"
#include "core/formats/obj_writer_header.hpp"
#include "core/scene_io.hpp"

static_assert(std::is_same_v<tinyobj::real_t, double>,
              "link tinyobjloader::tinyobjloader_double (it defines TINYOBJLOADER_USE_DOUBLE): the float build "
              "has another ABI and loses UTM-size coordinates");

namespace cullcheck::formats {
namespace {

struct VertexScan {
  std::vector<double> xyz;     // every `v` line's x, y, z, in file order
  std::optional<Vec2> origin;  // from our writer's comment
};

// tinyobjloader reads face indices with atoi into an int: 4294967298 wraps to 2, a valid vertex,
// so a face would silently use the wrong corner. Every number on an `f` line must fit: a vertex
// index within the vertex limit, texture and normal indices within an int.
void check_face_indices(const std::string& line, std::size_t line_no, const std::string& file) {
  const std::string field = "line " + std::to_string(line_no) + " (f)";
  const std::string text = line.substr(0, line.find('\0'));  // up to a NUL, as tinyobjloader reads it
  for (std::size_t at = text.find_first_not_of(" \t"); at != std::string::npos; at = text.find_first_not_of(" \t", at)) {
    const std::size_t token_end = std::min(text.find_first_of(" \t", at), text.size());
    // v, v/vt, v//vn or v/vt/vn; a part that is not a number is left to tinyobjloader's parse.
    for (int component = 0; at < token_end; ++component) {
      const std::size_t part_end = std::min(text.find('/', at), token_end);
      const std::string part = text.substr(at, part_end - at);
      char* next = nullptr;
      errno = 0;
      const long long index = part.empty() ? 0 : std::strtoll(part.c_str(), &next, 10);
      const long long limit = component == 0 ? static_cast<long long>(kMaxMeshVertices) : std::numeric_limits<int>::max();
      if (!part.empty() && next != part.c_str() && (errno == ERANGE || index > limit || index < -limit))
        throw InputError(file, field, std::string(component == 0 ? "vertex" : "texture or normal") + " index " + part +
                                          " is out of range");
      at = part_end + 1;
    }
    at = token_end;
  }
}

// Every `v x y z` line holds three finite numbers. Lines end as tinyobjloader ends them (\n,
// \r\n or a lone \r), so that both see the same `v` lines.
VertexScan scan_vertex_lines(const std::string& text, const std::string& file) {
  VertexScan scan;
  std::optional<Vec2>& origin = scan.origin;
  std::size_t line_no = 0, vertices = 0;
  for (std::size_t at = 0; at < text.size();) {
    std::size_t end = text.find_first_of("\r\n", at);
    if (end == std::string::npos) end = text.size();
    ++line_no;
    std::size_t i = text.find_first_not_of(" \t", at);
    if (i != std::string::npos && i >= end) i = std::string::npos;
    if (i != std::string::npos && i + 1 < end && text[i] == 'f' && (text[i + 1] == ' ' || text[i + 1] == '\t')) {
      check_face_indices(text.substr(i + 2, end - i - 2), line_no, file);
    } else if (i != std::string::npos && i + 1 < end && text[i] == 'v' && (text[i + 1] == ' ' || text[i + 1] == '\t')) {
      const std::string line = text.substr(i + 2, end - i - 2);
      const char* p = line.c_str();
      for (int k = 0; k < 3; ++k) {
        char* next = nullptr;
        const double x = std::strtod(p, &next);
        if (next == p)
          throw InputError(file, "line " + std::to_string(line_no) + " (v)", "needs three numbers x y z");
        if (!std::isfinite(x))
          throw InputError(file, "line " + std::to_string(line_no) + " (v)", "coordinate " + std::to_string(k) + " is not finite");
        scan.xyz.push_back(x);
        p = next;
      }
      if (++vertices > kMaxMeshVertices)
        throw InputError(file, "v", "has more than 50,000,000 vertices");
    } else if (i != std::string::npos && text.compare(i, std::char_traits<char>::length(detail::kObjOriginComment),
                                                      detail::kObjOriginComment) == 0) {
      const std::string line = text.substr(i, end - i);
      double x = 0, y = 0;
      if (std::sscanf(line.c_str() + std::char_traits<char>::length(detail::kObjOriginComment), "%lf %lf", &x, &y) == 2 &&
          std::isfinite(x) && std::isfinite(y) && std::abs(x) <= kMaxCoordinate && std::abs(y) <= kMaxCoordinate)
        origin = Vec2{x, y};
      else
        throw InputError(file, "line " + std::to_string(line_no) + " (origin comment)", "must give two finite numbers");
    }
    at = end + (end + 1 < text.size() && text[end] == '\r' && text[end + 1] == '\n' ? 2 : 1);
  }
  return scan;
}

}  // namespace

Scene read_obj(const std::string& path, const ImportOptions& options, ImportReport* report) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) throw InputError("file " + path, "(file)", "cannot be opened for reading");
  if (size > kMaxSceneFileBytes) throw InputError(path, "(file)", "is larger than the limit of 4 GiB");
  const std::string text = read_text_file(path);

  Scene scene;
  scene.provenance.generator = "file";
  const VertexScan scan = scan_vertex_lines(text, path);
  if (scan.origin) scene.origin = *scan.origin;

  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  if (!reader.ParseFromString(text, "", config)) {
    std::string err = reader.Error();
    while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
    throw InputError(path, "(document)", "is not valid OBJ: " + err);
  }
  ImportReport local;
  ImportReport& r = report ? *report : local;
  if (!reader.Warning().empty()) r.notes.push_back("tinyobjloader: " + reader.Warning());

  const std::vector<double>& parsed = reader.GetAttrib().vertices;
  const std::vector<double>& xyz = scan.xyz.size() == parsed.size() ? scan.xyz : parsed;
  if (&xyz == &parsed) r.notes.push_back("vertex scan and tinyobjloader disagree on the vertex count; tinyobjloader's values used");
  const std::size_t vertex_count = xyz.size() / 3;
  std::vector<detail::ImportedObject> objects;
  const auto& shapes = reader.GetShapes();
  for (std::size_t s = 0; s < shapes.size(); ++s) {
    const tinyobj::shape_t& shape = shapes[s];
    const std::string label = "group " + std::to_string(s) + (shape.name.empty() ? "" : " '" + shape.name + "'");
    if (!shape.lines.indices.empty() || !shape.points.indices.empty())
      r.notes.push_back(label + ": lines and points skipped (not triangles)");
    detail::ImportedObject o;
    o.source = label;
    o.name = shape.name;
    std::unordered_map<int, std::uint32_t> local_of;  // file vertex -> this object's vertex
    const auto& ids = shape.mesh.indices;
    std::size_t at = 0;
    for (std::size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
      const unsigned corners = shape.mesh.num_face_vertices[f];
      if (corners != 3 || at + 3 > ids.size())
        throw InputError(path + ": " + label, "f (face " + std::to_string(f + 1) + ")",
                         "has " + std::to_string(corners) + " corners after triangulation");
      std::array<std::uint32_t, 3> t{};
      for (int k = 0; k < 3; ++k) {
        const int v = ids[at + k].vertex_index;
        if (v < 0 || static_cast<std::size_t>(v) >= vertex_count)
          throw InputError(path + ": " + label, "f (face " + std::to_string(f + 1) + ")",
                           "vertex " + std::to_string(static_cast<long long>(v) + 1) + " is out of range (" +
                               std::to_string(vertex_count) + " vertices)");
        auto [it, added] = local_of.emplace(v, static_cast<std::uint32_t>(o.mesh.vertices.size()));
        if (added) {
          const double x = xyz[3 * v], y = xyz[3 * v + 1], z = xyz[3 * v + 2];
          o.mesh.vertices.push_back(options.obj_up == UpAxis::z ? Vec3{x, y, z} : Vec3{x, -z, y});
        }
        t[k] = it->second;
      }
      at += 3;
      o.mesh.triangles.push_back(t);
    }
    if (o.mesh.triangles.size() > kMaxTrianglesPerObject)
      throw InputError(path + ": " + label, "f", "exceeds the limit of 100,000,000 triangles per object");
    if (o.mesh.triangles.empty()) {
      r.notes.push_back(label + ": no triangles (skipped)");
      continue;
    }
    objects.push_back(std::move(o));
  }
  return detail::finish_import(std::move(objects), std::move(scene), options, &r, path);
}

}  // namespace cullcheck::formats
