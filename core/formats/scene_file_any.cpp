// Any scene file by its extension (mesh_formats.hpp: read_scene_file_any).
#include <algorithm>
#include <cctype>
#include <filesystem>

#include "core/errors.hpp"
#include "core/formats/mesh_formats.hpp"
#include "core/scene_io.hpp"

namespace cullcheck::formats {

Scene read_scene_file_any(const std::string& path, const ImportOptions& options, ImportReport* report) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".json") return read_scene_file(path);
  if (ext == ".glb" || ext == ".gltf") return read_gltf(path, options, report);
  if (ext == ".obj") return read_obj(path, options, report);
  throw InputError("file " + path, "(extension)",
                   "unknown scene file type '" + ext + "' (known: .json, .glb, .gltf, .obj)");
}

}  // namespace cullcheck::formats
