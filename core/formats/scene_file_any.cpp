// Any scene file by its extension (mesh_formats.hpp: read_scene_file_any).
#include <algorithm>
#include <cctype>
#include <filesystem>

#include "core/errors.hpp"
#include "core/formats/footprint_formats.hpp"
#include "core/formats/mesh_formats.hpp"
#include "core/scene_io.hpp"

namespace cullcheck::formats {

Scene read_scene_file_any(const std::string& path, const ImportOptions& options, ImportReport* report) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".geojson") return read_geojson(path, options.footprints, report);
  if (ext == ".json") {
    const std::string text = read_text_file(path);
    if (looks_like_geojson(text)) return geojson_from_text(text, options.footprints, report, "file " + path);
    if (looks_like_cityjson(text)) return cityjson_from_text(text, options.footprints, report, "file " + path);
    try {  // as read_scene_file, without reading the file a second time
      return scene_from_json_text(text);
    } catch (const InputError& e) {
      throw e.located(path);
    }
  }
  if (ext == ".glb" || ext == ".gltf") return read_gltf(path, options, report);
  if (ext == ".obj") return read_obj(path, options, report);
  throw InputError("file " + path, "(extension)",
                   "unknown scene file type '" + ext + "' (known: .json, .geojson, .glb, .gltf, .obj)");
}

}  // namespace cullcheck::formats
