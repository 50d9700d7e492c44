// glTF 2.0 import (mesh_formats.hpp: read_gltf), .glb and .gltf, through tinygltf's parser.
//
// tinygltf parses; everything it leaves unchecked is checked here before it is used: every index
// (scene, node, child, mesh, accessor, buffer view, buffer), every byte range, component types,
// finite numbers, node cycles. Extras are read from their original JSON text (tinygltf's Value
// truncates integers to int). Images are never decoded (a no-op image loader): cullcheck needs
// geometry only, and a hostile image is then no risk.
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "core/errors.hpp"
#include "core/formats/gltf_frame.hpp"
#include "core/formats/import_objects.hpp"
#include "core/formats/mesh_formats.hpp"
#include "core/scene_io.hpp"

namespace cullcheck::formats {
namespace {

using Matrix = std::array<double, 16>;  // column-major, as glTF
constexpr Matrix kIdentity = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

Matrix operator*(const Matrix& a, const Matrix& b) {
  Matrix c{};
  for (int col = 0; col < 4; ++col)
    for (int row = 0; row < 4; ++row) {
      double s = 0.0;
      for (int k = 0; k < 4; ++k) s += a[k * 4 + row] * b[col * 4 + k];
      c[col * 4 + row] = s;
    }
  return c;
}

Vec3 apply(const Matrix& m, Vec3 p) {
  return {m[0] * p.x + m[4] * p.y + m[8] * p.z + m[12], m[1] * p.x + m[5] * p.y + m[9] * p.z + m[13],
          m[2] * p.x + m[6] * p.y + m[10] * p.z + m[14]};
}

double determinant3(const Matrix& m) {
  return m[0] * (m[5] * m[10] - m[9] * m[6]) - m[4] * (m[1] * m[10] - m[9] * m[2]) + m[8] * (m[1] * m[6] - m[5] * m[2]);
}

std::string quoted(const std::string& name) { return name.empty() ? std::string() : " '" + name + "'"; }

struct Reader {
  const tinygltf::Model& model;
  std::string file;
  ImportReport& report;

  [[noreturn]] void fail(const std::string& object, const std::string& field, const std::string& problem) const {
    throw InputError(file + ": " + object, field, problem);
  }

  std::string node_label(std::size_t i) const { return "node " + std::to_string(i) + quoted(model.nodes[i].name); }
  std::string mesh_label(std::size_t i) const { return "mesh " + std::to_string(i) + quoted(model.meshes[i].name); }

  void check_finite(const std::vector<double>& v, std::size_t size, const std::string& object, const char* field) const {
    if (!v.empty() && v.size() != size)
      fail(object, field, "must have " + std::to_string(size) + " numbers (has " + std::to_string(v.size()) + ")");
    for (double x : v)
      if (!std::isfinite(x)) fail(object, field, "must be finite");
  }

  // The node's own transform: its matrix, or T * R * S (glTF 2.0 spec, 5.25).
  Matrix local_transform(std::size_t i) const {
    const tinygltf::Node& n = model.nodes[i];
    const std::string object = node_label(i);
    check_finite(n.matrix, 16, object, "matrix");
    check_finite(n.translation, 3, object, "translation");
    check_finite(n.rotation, 4, object, "rotation");
    check_finite(n.scale, 3, object, "scale");
    if (!n.matrix.empty()) {
      if (!n.translation.empty() || !n.rotation.empty() || !n.scale.empty())
        fail(object, "matrix", "must not be given together with translation, rotation or scale");
      Matrix m;
      std::copy(n.matrix.begin(), n.matrix.end(), m.begin());
      if (m[3] != 0.0 || m[7] != 0.0 || m[11] != 0.0 || m[15] != 1.0)
        fail(object, "matrix", "is not an affine transform (its last row must be 0, 0, 0, 1)");
      return m;
    }
    Matrix t = kIdentity, r = kIdentity, s = kIdentity;
    if (!n.translation.empty()) t[12] = n.translation[0], t[13] = n.translation[1], t[14] = n.translation[2];
    if (!n.scale.empty()) s[0] = n.scale[0], s[5] = n.scale[1], s[10] = n.scale[2];
    if (!n.rotation.empty()) {
      double x = n.rotation[0], y = n.rotation[1], z = n.rotation[2], w = n.rotation[3];
      const double norm = std::sqrt(x * x + y * y + z * z + w * w);
      if (!(norm > 0.0)) fail(object, "rotation", "is not a unit quaternion (its norm is 0)");
      x /= norm, y /= norm, z /= norm, w /= norm;  // the spec wants unit quaternions; be lenient
      r = {1 - 2 * (y * y + z * z), 2 * (x * y + z * w),     2 * (x * z - y * w),     0,
           2 * (x * y - z * w),     1 - 2 * (x * x + z * z), 2 * (y * z + x * w),     0,
           2 * (x * z + y * w),     2 * (y * z - x * w),     1 - 2 * (x * x + y * y), 0,
           0,                       0,                       0,                       1};
    }
    return t * r * s;
  }

  // Bytes of element k of an accessor, after checking every range it touches.
  struct View {
    const unsigned char* data = nullptr;
    std::size_t stride = 0, count = 0;
    const unsigned char* at(std::size_t k) const { return data + k * stride; }
  };

  View view_of(int index, std::size_t element_size, const std::string& object, const std::string& role) const {
    const std::string field = "accessors[" + std::to_string(index) + "] (" + role + ")";
    if (index < 0 || static_cast<std::size_t>(index) >= model.accessors.size())
      fail(object, role, "accessor " + std::to_string(index) + " does not exist (" + std::to_string(model.accessors.size()) + " accessors)");
    const tinygltf::Accessor& a = model.accessors[static_cast<std::size_t>(index)];
    if (a.sparse.isSparse) fail(object, field + ".sparse", "sparse accessors are not supported");
    if (a.bufferView < 0) fail(object, field + ".bufferView", "is missing (zero-filled accessors are not supported)");
    if (static_cast<std::size_t>(a.bufferView) >= model.bufferViews.size())
      fail(object, field + ".bufferView", "buffer view " + std::to_string(a.bufferView) + " does not exist");
    const tinygltf::BufferView& bv = model.bufferViews[static_cast<std::size_t>(a.bufferView)];
    const std::string bv_field = "bufferViews[" + std::to_string(a.bufferView) + "]";
    if (bv.buffer < 0 || static_cast<std::size_t>(bv.buffer) >= model.buffers.size())
      fail(object, bv_field + ".buffer", "buffer " + std::to_string(bv.buffer) + " does not exist");
    const std::vector<unsigned char>& data = model.buffers[static_cast<std::size_t>(bv.buffer)].data;
    if (bv.byteOffset > data.size() || bv.byteLength > data.size() - bv.byteOffset)
      fail(object, bv_field + ".byteLength",
           "bytes [" + std::to_string(bv.byteOffset) + ", +" + std::to_string(bv.byteLength) + ") lie beyond buffer " +
               std::to_string(bv.buffer) + " of " + std::to_string(data.size()) + " bytes");
    const std::size_t stride = bv.byteStride ? bv.byteStride : element_size;
    if (bv.byteStride != 0 && (stride < element_size || stride > 252 || stride % 4 != 0))
      fail(object, bv_field + ".byteStride", "must be a multiple of 4 in [" + std::to_string(std::max<std::size_t>(element_size, 4)) + ", 252]");
    if (a.count == 0) fail(object, field + ".count", "must be at least 1");
    if (a.count > kMaxMeshVertices * 3) fail(object, field + ".count", "exceeds the limit of 150,000,000 elements");
    if (a.byteOffset > bv.byteLength || (a.count - 1) > (bv.byteLength - a.byteOffset) / stride ||
        (a.count - 1) * stride + element_size > bv.byteLength - a.byteOffset)
      fail(object, field + ".count",
           std::to_string(a.count) + " elements from byte " + std::to_string(a.byteOffset) + " overrun buffer view " +
               std::to_string(a.bufferView) + " (" + std::to_string(bv.byteLength) + " bytes)");
    return {data.data() + bv.byteOffset + a.byteOffset, stride, a.count};
  }

  std::vector<Vec3> positions(int index, const std::string& object) const {
    if (index >= 0 && static_cast<std::size_t>(index) < model.accessors.size()) {
      const tinygltf::Accessor& a = model.accessors[static_cast<std::size_t>(index)];
      const std::string field = "accessors[" + std::to_string(index) + "] (POSITION)";
      if (a.type != TINYGLTF_TYPE_VEC3) fail(object, field + ".type", "must be VEC3");
      if (a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
        fail(object, field + ".componentType",
             "must be 5126 (float); got " + std::to_string(a.componentType) +
                 " (quantised positions, KHR_mesh_quantization, are not supported)");
    }
    const View v = view_of(index, 12, object, "POSITION");
    if (v.count > kMaxMeshVertices)
      fail(object, "accessors[" + std::to_string(index) + "] (POSITION).count", "exceeds the limit of 50,000,000 vertices per object");
    std::vector<Vec3> out(v.count);
    for (std::size_t k = 0; k < v.count; ++k) {
      float f[3];
      std::memcpy(f, v.at(k), 12);
      if constexpr (std::endian::native == std::endian::big)
        for (float& x : f) {
          const auto u = std::bit_cast<std::uint32_t>(x);
          x = std::bit_cast<float>((u >> 24) | ((u >> 8) & 0xFF00u) | ((u << 8) & 0xFF0000u) | (u << 24));
        }
      if (!std::isfinite(f[0]) || !std::isfinite(f[1]) || !std::isfinite(f[2]))
        fail(object, "accessors[" + std::to_string(index) + "] (POSITION)[" + std::to_string(k) + "]",
             "is not finite (" + std::to_string(f[0]) + ", " + std::to_string(f[1]) + ", " + std::to_string(f[2]) + ")");
      out[k] = {f[0], f[1], f[2]};
    }
    return out;
  }

  std::vector<std::uint32_t> indices(int index, const std::string& object) const {
    if (index < 0 || static_cast<std::size_t>(index) >= model.accessors.size())
      fail(object, "indices", "accessor " + std::to_string(index) + " does not exist");
    const tinygltf::Accessor& a = model.accessors[static_cast<std::size_t>(index)];
    const std::string field = "accessors[" + std::to_string(index) + "] (indices)";
    if (a.type != TINYGLTF_TYPE_SCALAR) fail(object, field + ".type", "must be SCALAR");
    std::size_t size = 0;
    switch (a.componentType) {
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: size = 1; break;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: size = 2; break;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: size = 4; break;
      default:
        fail(object, field + ".componentType",
             "must be 5121, 5123 or 5125 (unsigned byte, short, int); got " + std::to_string(a.componentType));
    }
    const View v = view_of(index, size, object, "indices");
    std::vector<std::uint32_t> out(v.count);
    for (std::size_t k = 0; k < v.count; ++k) {
      const unsigned char* p = v.at(k);  // little-endian by the spec
      std::uint32_t x = 0;
      for (std::size_t b = 0; b < size; ++b) x |= std::uint32_t{p[b]} << (8 * b);
      out[k] = x;
    }
    return out;
  }

  // Appends one primitive's triangles, transformed by `world` and turned z up, to `out`.
  void append_primitive(std::size_t mesh, std::size_t p, const Matrix& world, const std::string& object, MeshObject& out) const {
    const tinygltf::Primitive& prim = model.meshes[mesh].primitives[p];
    const std::string where = object + ", " + mesh_label(mesh) + " primitive " + std::to_string(p);
    if (prim.mode >= TINYGLTF_MODE_POINTS && prim.mode <= TINYGLTF_MODE_LINE_STRIP) {
      report.notes.push_back(where + ": skipped (mode " + std::to_string(prim.mode) + " draws points or lines, not triangles)");
      return;
    }
    if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != TINYGLTF_MODE_TRIANGLE_STRIP && prim.mode != TINYGLTF_MODE_TRIANGLE_FAN)
      fail(where, "mode", "must be 0-6 (got " + std::to_string(prim.mode) + ")");
    const auto pos = prim.attributes.find("POSITION");
    if (pos == prim.attributes.end()) fail(where, "attributes.POSITION", "is missing");
    const std::vector<Vec3> local = positions(pos->second, where);
    std::vector<std::uint32_t> order;
    if (prim.indices >= 0) {
      order = indices(prim.indices, where);
      for (std::size_t k = 0; k < order.size(); ++k)
        if (order[k] >= local.size())
          fail(where, "accessors[" + std::to_string(prim.indices) + "] (indices)[" + std::to_string(k) + "]",
               "index " + std::to_string(order[k]) + " is out of range (" + std::to_string(local.size()) + " vertices)");
    } else {
      order.resize(local.size());
      for (std::size_t k = 0; k < order.size(); ++k) order[k] = static_cast<std::uint32_t>(k);
    }
    if (!prim.targets.empty()) report.notes.push_back(where + ": morph targets ignored (base positions used)");

    // The limits before anything is allocated for them: a strip of 150,000,000 one-byte indices
    // would otherwise build 1.8 GB of triangles only to refuse them.
    const std::size_t corners = order.size();
    const std::size_t new_triangles = prim.mode == TINYGLTF_MODE_TRIANGLES ? corners / 3 : (corners >= 3 ? corners - 2 : 0);
    if (out.vertices.size() + local.size() > kMaxMeshVertices)
      fail(object, "vertices", "exceeds the limit of 50,000,000 vertices per object");
    if (out.triangles.size() + new_triangles > kMaxTrianglesPerObject)
      fail(object, "triangles", "exceeds the limit of 100,000,000 triangles per object");

    std::vector<std::array<std::uint32_t, 3>> triangles;
    triangles.reserve(new_triangles);
    if (prim.mode == TINYGLTF_MODE_TRIANGLES) {
      if (order.size() % 3 != 0)
        fail(where, prim.indices >= 0 ? "accessors[" + std::to_string(prim.indices) + "] (indices).count" : "attributes.POSITION",
             std::to_string(order.size()) + " vertices do not make whole triangles");
      for (std::size_t k = 0; k + 2 < order.size(); k += 3) triangles.push_back({order[k], order[k + 1], order[k + 2]});
    } else if (prim.mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
      // glTF 2.0 spec 3.7.2.1: p_i = {v_i, v_{i+(1+i%2)}, v_{i+(2-i%2)}}, keeping one winding.
      for (std::size_t k = 0; k + 2 < order.size(); ++k)
        triangles.push_back({order[k], order[k + 1 + k % 2], order[k + 2 - k % 2]});
    } else {
      // p_i = {v_{i+1}, v_{i+2}, v_0}
      for (std::size_t k = 0; k + 2 < order.size(); ++k) triangles.push_back({order[k + 1], order[k + 2], order[0]});
    }

    // Merged instances and primitives are offset by the vertices before them; the limit above
    // keeps base + index (both below it) within 32 bits.
    static_assert(2 * kMaxMeshVertices <= std::numeric_limits<std::uint32_t>::max());
    const auto base = static_cast<std::uint32_t>(out.vertices.size());
    for (const Vec3& v : local) out.vertices.push_back(detail::y_up_to_z_up(apply(world, v)));
    // A mirroring transform turns faces inside out; swap two corners to keep them facing out.
    const bool mirrored = determinant3(world) < 0.0;
    for (const auto& t : triangles) {
      if (mirrored) out.triangles.push_back({base + t[0], base + t[2], base + t[1]});
      else out.triangles.push_back({base + t[0], base + t[1], base + t[2]});
    }
  }

  void append_mesh(std::size_t mesh, const Matrix& world, const std::string& object, MeshObject& out) const {
    for (std::size_t p = 0; p < model.meshes[mesh].primitives.size(); ++p) append_primitive(mesh, p, world, object, out);
  }

  // World transforms of every node reached from the roots, by depth-first search; a node reached
  // twice is a cycle or a second parent, both forbidden by the spec (5.25: "nodes MUST NOT
  // contain cycles ... a node MUST have at most one parent"). Iterative: a hostile file may nest
  // a million levels deep.
  std::vector<std::optional<Matrix>> world_transforms(const std::vector<int>& roots, const std::string& roots_field) const {
    const std::size_t n = model.nodes.size();
    std::vector<std::optional<Matrix>> world(n);
    std::vector<std::uint8_t> state(n, 0);  // 0 unseen, 1 on the current path, 2 done
    struct Frame {
      std::size_t node, next_child;
    };
    for (std::size_t r = 0; r < roots.size(); ++r) {
      const int root = roots[r];
      if (root < 0 || static_cast<std::size_t>(root) >= n)
        fail("scene", roots_field + "[" + std::to_string(r) + "]", "node " + std::to_string(root) + " does not exist");
      if (state[root] != 0) fail(node_label(root), "(parent)", "is reached twice from the scene's root nodes");
      world[root] = local_transform(root);
      state[root] = 1;
      std::vector<Frame> stack{{static_cast<std::size_t>(root), 0}};
      while (!stack.empty()) {
        Frame& f = stack.back();
        const std::vector<int>& children = model.nodes[f.node].children;
        if (f.next_child == children.size()) {
          state[f.node] = 2;
          stack.pop_back();
          continue;
        }
        const std::size_t k = f.next_child++;
        const int c = children[k];
        const std::size_t parent = f.node;
        if (c < 0 || static_cast<std::size_t>(c) >= n)
          fail(node_label(parent), "children[" + std::to_string(k) + "]", "node " + std::to_string(c) + " does not exist");
        if (state[c] == 1)
          fail(node_label(parent), "children[" + std::to_string(k) + "]",
               "makes a cycle: node " + std::to_string(c) + " is its own ancestor");
        if (state[c] == 2) fail(node_label(c), "(parent)", "has two parents (node " + std::to_string(parent) + " is the second)");
        world[c] = *world[parent] * local_transform(c);
        state[c] = 1;
        stack.push_back({static_cast<std::size_t>(c), 0});
      }
    }
    return world;
  }
};

bool load_image_skipped(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
  return true;
}

std::uint32_t le32(const std::string& bytes, std::size_t at) {
  std::uint32_t x = 0;
  for (int b = 0; b < 4; ++b) x |= std::uint32_t{static_cast<unsigned char>(bytes[at + b])} << (8 * b);
  return x;
}

// The .glb container's own fields, checked before tinygltf so that a truncated file names them.
void check_glb_header(const std::string& bytes, const std::string& file) {
  if (bytes.size() < 20) throw InputError(file, "glb header", "is truncated (" + std::to_string(bytes.size()) + " bytes; at least 20 needed)");
  if (le32(bytes, 4) != 2) throw InputError(file, "glb header.version", "must be 2 (got " + std::to_string(le32(bytes, 4)) + ")");
  const std::uint32_t length = le32(bytes, 8);
  if (length != bytes.size())
    throw InputError(file, "glb header.length",
                     "says " + std::to_string(length) + " bytes but the file holds " + std::to_string(bytes.size()) +
                         (length > bytes.size() ? " (truncated)" : ""));
  const std::uint64_t json_end = 20ull + le32(bytes, 12);
  if (le32(bytes, 16) != 0x4E4F534A) throw InputError(file, "glb chunk 0.type", "must be JSON");
  if (json_end > bytes.size())
    throw InputError(file, "glb chunk 0.length", "says " + std::to_string(le32(bytes, 12)) + " bytes, beyond the end of the file (truncated)");
  if (json_end < bytes.size()) {
    if (json_end + 8 > bytes.size()) throw InputError(file, "glb chunk 1", "is truncated (no chunk header)");
    if (json_end + 8 + le32(bytes, json_end) > bytes.size())
      throw InputError(file, "glb chunk 1.length",
                       "says " + std::to_string(le32(bytes, json_end)) + " bytes, beyond the end of the file (truncated)");
  }
}

bool geometry_extension(const std::string& name) {
  // Extensions that change what the geometry is; anything else (materials, textures, lights)
  // only changes how it looks, which cullcheck does not need.
  return name == "KHR_draco_mesh_compression" || name == "KHR_mesh_quantization" || name == "EXT_meshopt_compression" ||
         name == "EXT_mesh_gpu_instancing";
}

// asset.extras.cullcheck, written by write_glb: the world origin and the provenance.
void read_asset_extras(const tinygltf::Model& model, Scene& scene, const std::string& file) {
  if (model.asset.extras_json_string.empty()) return;
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(model.asset.extras_json_string);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file, "asset.extras", std::string("is not valid JSON: ") + e.what());
  }
  if (!j.is_object() || !j.contains("cullcheck") || !j["cullcheck"].is_object()) return;
  const nlohmann::json& c = j["cullcheck"];
  if (auto it = c.find("origin"); it != c.end()) {
    if (!it->is_array() || it->size() != 2 || !(*it)[0].is_number() || !(*it)[1].is_number())
      throw InputError(file, "asset.extras.cullcheck.origin", "must be [x, y]");
    scene.origin = {(*it)[0].get<double>(), (*it)[1].get<double>()};
    if (!std::isfinite(scene.origin.x) || !std::isfinite(scene.origin.y) || std::abs(scene.origin.x) > kMaxCoordinate ||
        std::abs(scene.origin.y) > kMaxCoordinate)
      throw InputError(file, "asset.extras.cullcheck.origin", "must be finite and within 1e9 m");
  }
  if (auto it = c.find("provenance"); it != c.end() && it->is_object()) {
    if (auto g = it->find("generator"); g != it->end() && g->is_string()) scene.provenance.generator = *g;
    if (auto s = it->find("seed"); s != it->end()) {
      try {
        std::size_t used = 0;
        const std::string text = s->is_string() ? s->get<std::string>() : s->dump();
        scene.provenance.seed = std::stoull(text, &used);
        if (used != text.size()) throw std::invalid_argument("trailing text");
      } catch (const std::exception&) {
        throw InputError(file, "asset.extras.cullcheck.provenance.seed", "must be a non-negative 64-bit integer");
      }
    }
    if (auto p = it->find("parameters"); p != it->end()) scene.provenance.parameters_json = p->dump();
  }
}

}  // namespace

Scene read_gltf(const std::string& path, const ImportOptions& options, ImportReport* report) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) throw InputError("file " + path, "(file)", "cannot be opened for reading");
  if (size > kMaxSceneFileBytes) throw InputError(path, "(file)", "is larger than the limit of 4 GiB");
  const std::string bytes = read_text_file(path);
  const bool binary = bytes.size() >= 4 && bytes.compare(0, 4, "glTF") == 0;
  if (binary) check_glb_header(bytes, path);

  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  loader.SetStoreOriginalJSONForExtrasAndExtensions(true);
  loader.SetImageLoader(&load_image_skipped, nullptr);
  std::string err, warn;
  const std::string base_dir = std::filesystem::path(path).parent_path().string();
  bool ok = false;
  try {
    ok = binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(bytes.data()),
                                              static_cast<unsigned int>(bytes.size()), base_dir)
                : loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(), static_cast<unsigned int>(bytes.size()), base_dir);
  } catch (const std::exception& e) {
    err = e.what();
  }
  while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
  if (!ok) throw InputError(path, "(document)", "is not valid glTF: " + (err.empty() ? std::string("tinygltf refused it") : err));

  ImportReport local;
  ImportReport& r = report ? *report : local;
  if (!warn.empty()) r.notes.push_back("tinygltf: " + warn);
  if (!model.images.empty()) r.notes.push_back(std::to_string(model.images.size()) + " images ignored (geometry only)");
  for (const std::string& e : model.extensionsRequired)
    if (geometry_extension(e)) throw InputError(path, "extensionsRequired", "needs " + e + ", which cullcheck does not support");
  if (model.nodes.size() > kMaxNodes) throw InputError(path, "nodes", "has more than 50,000,000 entries");

  Scene scene;
  scene.provenance.generator = "file";
  read_asset_extras(model, scene, path);

  const Reader reader{model, path, r};
  // The default scene's root nodes, or (no default scene) every node that is no one's child.
  std::vector<int> roots;
  std::string roots_field;
  if (model.defaultScene >= 0) {
    if (static_cast<std::size_t>(model.defaultScene) >= model.scenes.size())
      throw InputError(path, "scene", "scene " + std::to_string(model.defaultScene) + " does not exist");
    roots = model.scenes[static_cast<std::size_t>(model.defaultScene)].nodes;
    roots_field = "scenes[" + std::to_string(model.defaultScene) + "].nodes";
  } else {
    std::vector<bool> is_child(model.nodes.size(), false);
    for (const tinygltf::Node& n : model.nodes)
      for (int c : n.children)
        if (c >= 0 && static_cast<std::size_t>(c) < model.nodes.size()) is_child[c] = true;
    for (std::size_t i = 0; i < model.nodes.size(); ++i)
      if (!is_child[i]) roots.push_back(static_cast<int>(i));
    roots_field = "nodes";
  }
  const auto world = reader.world_transforms(roots, roots_field);

  std::vector<detail::ImportedObject> objects;
  if (options.ids == IdSource::node) {
    for (std::size_t i = 0; i < model.nodes.size(); ++i) {
      const tinygltf::Node& n = model.nodes[i];
      if (!world[i] || n.mesh < 0) continue;
      const std::string label = reader.node_label(i);
      if (static_cast<std::size_t>(n.mesh) >= model.meshes.size())
        throw InputError(path + ": " + label, "mesh", "mesh " + std::to_string(n.mesh) + " does not exist");
      detail::ImportedObject o;
      o.source = label;
      o.name = n.name.empty() ? model.meshes[n.mesh].name : n.name;
      o.given = detail::parse_given_extras(n.extras_json_string, path + ": " + label);
      reader.append_mesh(static_cast<std::size_t>(n.mesh), *world[i], label, o.mesh);
      if (o.mesh.triangles.empty()) {
        r.notes.push_back(label + ": no triangles (skipped)");
        continue;
      }
      objects.push_back(std::move(o));
    }
  } else {
    std::vector<std::optional<detail::ImportedObject>> by_mesh(model.meshes.size());
    for (std::size_t i = 0; i < model.nodes.size(); ++i) {
      const tinygltf::Node& n = model.nodes[i];
      if (!world[i] || n.mesh < 0) continue;
      if (static_cast<std::size_t>(n.mesh) >= model.meshes.size())
        throw InputError(path + ": " + reader.node_label(i), "mesh", "mesh " + std::to_string(n.mesh) + " does not exist");
      auto& slot = by_mesh[static_cast<std::size_t>(n.mesh)];
      const std::string label = reader.mesh_label(static_cast<std::size_t>(n.mesh));
      if (!slot) {
        slot.emplace();
        slot->source = label;
        slot->name = model.meshes[n.mesh].name;
        slot->given = detail::parse_given_extras(model.meshes[n.mesh].extras_json_string, path + ": " + label);
      }
      reader.append_mesh(static_cast<std::size_t>(n.mesh), *world[i], label + " (instance at " + reader.node_label(i) + ")", slot->mesh);
    }
    for (auto& slot : by_mesh) {
      if (!slot) continue;
      if (slot->mesh.triangles.empty()) {
        r.notes.push_back(slot->source + ": no triangles (skipped)");
        continue;
      }
      objects.push_back(std::move(*slot));
    }
  }
  return detail::finish_import(std::move(objects), std::move(scene), options, &r, path);
}

}  // namespace cullcheck::formats
