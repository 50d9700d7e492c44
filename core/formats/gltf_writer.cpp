// glTF 2.0 binary export (mesh_formats.hpp: write_glb), through tinygltf's model and writer.
//
// Layout: node 0 is the root `cullcheck_scene` (matrix kZUpToYUp, children = every object); node
// k > 0 is one object with its own mesh of one TRIANGLES primitive: POSITION (float32 VEC3, with
// min/max) and indices (uint16 when the object has at most 65,535 vertices, else uint32; glTF
// forbids the all-ones value). Two buffer views hold every object's data: positions (stride 12)
// and indices (each object's block padded to 4 bytes, so a uint32 block stays aligned). No
// material: glTF's default material applies, and validators accept its absence.
//
// Determinism: tinygltf serialises through nlohmann::json, whose objects are ordered maps and
// whose numbers print as shortest round-trip text; vertex bytes are little-endian float32.
#include <bit>
#include <cstring>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <tiny_gltf.h>

#include "core/errors.hpp"
#include "core/formats/exported_object.hpp"
#include "core/formats/gltf_frame.hpp"
#include "core/formats/mesh_formats.hpp"
#include "core/scene_io.hpp"

namespace cullcheck::formats {
namespace {

using tinygltf::Value;

constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;

template <class T>
void append_le(std::vector<unsigned char>& out, T value) {
  unsigned char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  if constexpr (std::endian::native == std::endian::big) std::reverse(bytes, bytes + sizeof(T));
  out.insert(out.end(), bytes, bytes + sizeof(T));
}

Value number(double v) { return Value(v == 0.0 ? 0.0 : v); }  // no "-0.0" in the file

// Ids above INT_MAX go as doubles (exact below 2^53): tinygltf's Value has no wider integer.
Value id_value(ObjectId id) {
  return id <= static_cast<ObjectId>(std::numeric_limits<int>::max()) ? Value(static_cast<int>(id))
                                                                        : Value(static_cast<double>(id));
}

Value from_json(const nlohmann::json& j) {
  switch (j.type()) {
    case nlohmann::json::value_t::object: {
      Value::Object o;
      for (auto it = j.begin(); it != j.end(); ++it) o.emplace(it.key(), from_json(it.value()));
      return Value(std::move(o));
    }
    case nlohmann::json::value_t::array: {
      Value::Array a;
      for (const auto& e : j) a.push_back(from_json(e));
      return Value(std::move(a));
    }
    case nlohmann::json::value_t::string: return Value(j.get<std::string>());
    case nlohmann::json::value_t::boolean: return Value(j.get<bool>());
    case nlohmann::json::value_t::number_integer:
    case nlohmann::json::value_t::number_unsigned: {
      const double d = j.get<double>();
      if (d >= std::numeric_limits<int>::min() && d <= std::numeric_limits<int>::max()) return Value(j.get<int>());
      return Value(d);
    }
    case nlohmann::json::value_t::number_float: return number(j.get<double>());
    default: return Value();
  }
}

// asset.extras.cullcheck: what a re-import needs beyond the geometry. The seed goes as text
// because a 64-bit seed fits neither tinygltf's int nor a double.
Value asset_extras(const Scene& scene) {
  nlohmann::json parameters;
  try {
    parameters = nlohmann::json::parse(scene.provenance.parameters_json);
  } catch (const nlohmann::json::exception&) {
    parameters = scene.provenance.parameters_json;
  }
  Value::Object provenance{{"generator", Value(scene.provenance.generator)},
                           {"seed", Value(std::to_string(scene.provenance.seed))},
                           {"parameters", from_json(parameters)}};
  Value::Object cullcheck{
      {"format", Value(std::string("cullcheck-glb"))},
      {"version", Value(1)},
      {"units", Value(std::string("metres"))},
      {"frame", Value(std::string("vertices are scene-local, z up; node cullcheck_scene turns z up into +Y up; "
                                  "world = local + origin"))},
      {"origin", Value(Value::Array{number(scene.origin.x), number(scene.origin.y)})},
      {"provenance", Value(std::move(provenance))}};
  return Value(Value::Object{{"cullcheck", Value(std::move(cullcheck))}});
}

struct Buffers {
  std::vector<unsigned char> positions, indices;
};

// One object: accessors, mesh and node appended to the model.
void add_object(tinygltf::Model& model, Buffers& buffers, const MeshObject& m, const std::string& name,
                Value node_extras, Value mesh_extras) {
  tinygltf::Accessor position;
  position.bufferView = 0;
  position.byteOffset = buffers.positions.size();
  position.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  position.type = TINYGLTF_TYPE_VEC3;
  position.count = m.vertices.size();
  std::array<float, 3> lo{HUGE_VALF, HUGE_VALF, HUGE_VALF}, hi{-HUGE_VALF, -HUGE_VALF, -HUGE_VALF};
  for (const Vec3& v : m.vertices) {
    const std::array<float, 3> f{static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z)};
    for (int k = 0; k < 3; ++k) {
      append_le(buffers.positions, f[k]);
      lo[k] = std::min(lo[k], f[k]), hi[k] = std::max(hi[k], f[k]);
    }
  }
  position.minValues = {lo[0], lo[1], lo[2]};  // of the float32 values, as glTF requires
  position.maxValues = {hi[0], hi[1], hi[2]};

  tinygltf::Accessor index;
  index.bufferView = 1;
  index.byteOffset = buffers.indices.size();
  index.type = TINYGLTF_TYPE_SCALAR;
  index.count = 3 * m.triangles.size();
  const bool narrow = m.vertices.size() <= 65535;
  index.componentType = narrow ? TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT : TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  for (const auto& t : m.triangles)
    for (std::uint32_t k : t) {
      if (narrow) append_le(buffers.indices, static_cast<std::uint16_t>(k));
      else append_le(buffers.indices, k);
    }
  while (buffers.indices.size() % 4 != 0) buffers.indices.push_back(0);

  const int first_accessor = static_cast<int>(model.accessors.size());
  model.accessors.push_back(std::move(position));
  model.accessors.push_back(std::move(index));

  tinygltf::Primitive primitive;
  primitive.attributes["POSITION"] = first_accessor;
  primitive.indices = first_accessor + 1;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  tinygltf::Mesh mesh;
  mesh.name = name;
  mesh.primitives.push_back(std::move(primitive));
  mesh.extras = std::move(mesh_extras);
  model.meshes.push_back(std::move(mesh));

  tinygltf::Node node;
  node.name = name;
  node.mesh = static_cast<int>(model.meshes.size() - 1);
  node.extras = std::move(node_extras);
  model.nodes.push_back(std::move(node));
  model.nodes[0].children.push_back(static_cast<int>(model.nodes.size() - 1));
}

tinygltf::Model scene_model(const Scene& scene) {
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "cullcheck";
  model.asset.extras = asset_extras(scene);

  tinygltf::Node root;
  root.name = detail::kRootNodeName;
  root.matrix.assign(detail::kZUpToYUp.begin(), detail::kZUpToYUp.end());
  model.nodes.push_back(std::move(root));
  model.nodes.reserve(scene.object_count() + 1);
  model.meshes.reserve(scene.object_count());
  model.accessors.reserve(2 * scene.object_count());

  Buffers buffers;
  for (const Building& b : scene.buildings) {
    Value::Array footprint;
    footprint.reserve(b.footprint.size());
    for (Vec2 p : b.footprint) footprint.push_back(Value(Value::Array{number(p.x), number(p.y)}));
    Value::Object extras{{"cullcheck_id", id_value(b.id)},
                         {"kind", Value(std::string("building"))},
                         {"footprint", Value(std::move(footprint))},
                         {"height", number(b.height)}};
    Value::Object mesh_extras{{"cullcheck_id", id_value(b.id)}, {"kind", Value(std::string("building"))}};
    add_object(model, buffers, detail::building_surface(b), detail::building_name(b.id), Value(std::move(extras)),
               Value(std::move(mesh_extras)));
  }
  for (const MeshObject& m : scene.meshes) {
    Value::Object extras{{"cullcheck_id", id_value(m.id)}, {"kind", Value(std::string("mesh"))}};
    Value::Object mesh_extras = extras;
    if (!m.name.empty()) extras.emplace("name", Value(m.name));  // the node is named mesh_<id>
    add_object(model, buffers, m, detail::mesh_name(m.id), Value(std::move(extras)), Value(std::move(mesh_extras)));
  }

  if (buffers.positions.size() + buffers.indices.size() > (std::size_t{1} << 32) - (std::size_t{1} << 28))
    throw InputError("scene", "(size)", "is too large for one .glb file (4 GiB)");
  if (!buffers.positions.empty()) {
    tinygltf::BufferView positions;
    positions.buffer = 0;
    positions.byteOffset = 0;
    positions.byteLength = buffers.positions.size();
    positions.byteStride = 12;  // required when several accessors share a vertex buffer view
    positions.target = kArrayBuffer;
    tinygltf::BufferView indices;
    indices.buffer = 0;
    indices.byteOffset = buffers.positions.size();  // a multiple of 4
    indices.byteLength = buffers.indices.size();
    indices.target = kElementArrayBuffer;
    model.bufferViews = {std::move(positions), std::move(indices)};
    tinygltf::Buffer buffer;
    buffer.data = std::move(buffers.positions);
    buffer.data.insert(buffer.data.end(), buffers.indices.begin(), buffers.indices.end());
    model.buffers.push_back(std::move(buffer));
  }

  tinygltf::Scene s;
  s.name = "cullcheck";
  s.nodes = {0};
  model.scenes.push_back(std::move(s));
  model.defaultScene = 0;
  return model;
}

}  // namespace

std::string glb_bytes(const Scene& scene) {
  const tinygltf::Model model = scene_model(scene);
  tinygltf::TinyGLTF writer;
  std::ostringstream out(std::ios::binary);
  if (!writer.WriteGltfSceneToStream(&model, out, false, true) || !out)
    throw InputError("scene", "(glb)", "tinygltf could not serialise the scene");
  return std::move(out).str();
}

void write_glb(const Scene& scene, const std::string& path) { write_text_file_atomically(path, glb_bytes(scene)); }

}  // namespace cullcheck::formats
