// Hand-built glTF files for the formats tests, through tinygltf's model API (the same library
// the reader uses to parse, but none of cullcheck's writer: a bug in write_glb cannot hide here).
#pragma once

#include <array>
#include <cstring>
#include <filesystem>
#include <string>
#include <tiny_gltf.h>
#include <unistd.h>
#include <vector>

namespace cullcheck::formats::testing {

class GltfBuilder {
 public:
  GltfBuilder() {
    model.asset.version = "2.0";
    model.buffers.emplace_back();
  }

  // An accessor over new bytes in buffer 0 with its own buffer view.
  int accessor(const void* data, std::size_t bytes, int component_type, int type, std::size_t count) {
    std::vector<unsigned char>& buffer = model.buffers[0].data;
    while (buffer.size() % 4 != 0) buffer.push_back(0);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = buffer.size();
    view.byteLength = bytes;
    const auto* p = static_cast<const unsigned char*>(data);
    buffer.insert(buffer.end(), p, p + bytes);
    model.bufferViews.push_back(view);
    tinygltf::Accessor a;
    a.bufferView = static_cast<int>(model.bufferViews.size() - 1);
    a.componentType = component_type;
    a.type = type;
    a.count = count;
    model.accessors.push_back(a);
    return static_cast<int>(model.accessors.size() - 1);
  }

  int positions(const std::vector<std::array<float, 3>>& v) {
    return accessor(v.data(), v.size() * 12, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, v.size());
  }
  int indices(const std::vector<std::uint16_t>& i) {
    return accessor(i.data(), i.size() * 2, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_SCALAR, i.size());
  }

  int mesh(const std::string& name, int position_accessor, int index_accessor = -1, int mode = TINYGLTF_MODE_TRIANGLES) {
    tinygltf::Primitive p;
    p.attributes["POSITION"] = position_accessor;
    p.indices = index_accessor;
    p.mode = mode;
    tinygltf::Mesh m;
    m.name = name;
    m.primitives.push_back(p);
    model.meshes.push_back(m);
    return static_cast<int>(model.meshes.size() - 1);
  }

  int node(const std::string& name, int mesh_index = -1) {
    tinygltf::Node n;
    n.name = name;
    n.mesh = mesh_index;
    model.nodes.push_back(n);
    return static_cast<int>(model.nodes.size() - 1);
  }

  // One scene (the default) holding `roots`.
  void scene(const std::vector<int>& roots) {
    tinygltf::Scene s;
    s.nodes = roots;
    model.scenes = {s};
    model.defaultScene = 0;
  }

  void write(const std::string& path, bool binary = true) const {
    tinygltf::TinyGLTF writer;
    if (!writer.WriteGltfSceneToFile(&model, path, false, true, false, binary)) throw std::runtime_error("cannot write " + path);
  }

  tinygltf::Model model;
};

// A per-process scratch folder for the test files, removed when the test program ends.
inline std::filesystem::path scratch_dir() {
  static const struct Dir {
    std::filesystem::path path =
        std::filesystem::temp_directory_path() / ("cullcheck_formats_test_" + std::to_string(::getpid()));
    Dir() { std::filesystem::create_directories(path); }
    ~Dir() {
      std::error_code ec;
      std::filesystem::remove_all(path, ec);
    }
  } dir;
  return dir.path;
}

inline std::string scratch_path(const std::string& name) { return (scratch_dir() / name).string(); }

}  // namespace cullcheck::formats::testing
