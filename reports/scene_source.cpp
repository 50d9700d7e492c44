#include "reports/scene_source.hpp"

#include <sstream>

#include <nlohmann/json.hpp>

#include "core/errors.hpp"
#include "core/scene_io.hpp"
#include "generators/city.hpp"

namespace cullcheck {

Scene SceneSource::load(formats::ImportReport* report) const {
  if (!file.empty()) {
    formats::ImportOptions options;
    options.ids = mesh_ids;
    options.obj_up = obj_up;
    options.footprints = footprints;
    return formats::read_scene_file_any(file, options, report);
  }
  nlohmann::json params;
  try {
    params = nlohmann::json::parse(parameters_json);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError("generator", "params", std::string("is not valid JSON: ") + e.what());
  }
  return generators::make_city(generator, seed, params);
}

std::string SceneSource::replay_flags() const {
  if (!file.empty()) {
    std::string flags = "--scene " + shell_quote(file);
    if (mesh_ids != formats::IdSource::node) flags += " --mesh-ids mesh";
    if (obj_up != formats::UpAxis::z) flags += " --obj-up y";
    const formats::FootprintOptions defaults;
    if (!footprints.height_attribute.empty()) flags += " --height-attribute " + shell_quote(footprints.height_attribute);
    if (!footprints.storeys_attribute.empty()) flags += " --storeys-attribute " + shell_quote(footprints.storeys_attribute);
    if (footprints.storey_height != defaults.storey_height) flags += " --storey-height " + round_trip_text(footprints.storey_height);
    if (footprints.missing_height) flags += " --missing-height " + round_trip_text(*footprints.missing_height);
    if (!footprints.crs.empty()) flags += " --crs " + shell_quote(footprints.crs);
    if (footprints.cityjson_buildings) flags += " --cityjson-buildings";
    else if (footprints.cityjson_meshes) flags += " --cityjson-meshes";
    return flags;
  }
  std::string flags = "--generator " + generator + " --seed " + std::to_string(seed);
  if (parameters_json != "{}" && !parameters_json.empty()) flags += " --params " + shell_quote(parameters_json);
  return flags;
}

}  // namespace cullcheck
