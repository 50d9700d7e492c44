// Generators by name, for the CLI and for replay commands (see city.hpp).
#include <nlohmann/json.hpp>

#include "core/errors.hpp"
#include "generators/city.hpp"
#include "generators/detailed_buildings.hpp"
#include "generators/kept_cases.hpp"
#include "generators/params_json.hpp"
#include "generators/plan_scenes.hpp"

namespace cullcheck::generators {
namespace {

std::string joined_names() {
  std::string s;
  for (const std::string& n : city_generator_names()) s += (s.empty() ? "" : ", ") + n;
  return s;
}

[[noreturn]] void unknown_generator(const std::string& name) {
  throw InputError("generator", "name", "unknown generator '" + name + "' (known: " + joined_names() + ")");
}

template <class Params>
Params overlaid(Params defaults, const nlohmann::json& params, const std::string& name) {
  overlay_params_json(defaults, params, "generator", name);
  validate(defaults, name);
  return defaults;
}

// The defaults a Manhattan-family generator starts from.
std::optional<ManhattanParams> manhattan_defaults(const std::string& name) {
  if (name == "manhattan") return ManhattanParams{};
  if (name == "plaza") return plaza_params();
  if (name == "default") return default_city_params();
  return std::nullopt;
}

}  // namespace

const std::vector<std::string>& city_generator_names() {
  static const std::vector<std::string> names = {"default", "manhattan", "plaza", "scatter", "irregular", "thesis", "openings", "kept", "slot_city", "star_block_city", "detailed"};
  return names;
}

nlohmann::json resolved_city_params(const std::string& name, const nlohmann::json& params) {
  if (auto m = manhattan_defaults(name)) return params_to_json(overlaid(*m, params, name));
  if (name == "scatter") return params_to_json(overlaid(ScatterParams{}, params, name));
  if (name == "irregular") return params_to_json(overlaid(IrregularParams{}, params, name));
  if (name == "thesis") return params_to_json(overlaid(ThesisParams{}, params, name));
  if (name == "openings") return params_to_json(overlaid(OpeningsParams{}, params, name));
  if (name == "kept") return params_to_json(overlaid(KeptParams{}, params, name));
  if (name == "slot_city") return params_to_json(overlaid(SlotCityParams{}, params, name));
  if (name == "star_block_city") return params_to_json(overlaid(StarBlockParams{}, params, name));
  if (name == "detailed") return params_to_json(overlaid(DetailedCityParams{}, params, name));
  unknown_generator(name);
}

Scene make_city(const std::string& name, std::uint64_t seed, const nlohmann::json& params) {
  if (auto m = manhattan_defaults(name)) {
    const ManhattanParams p = overlaid(*m, params, name);
    Scene scene = name == "plaza" ? plaza_city(p, seed) : manhattan_city(p, seed);
    scene.provenance.generator = name;
    return scene;
  }
  if (name == "scatter") return scatter_city(overlaid(ScatterParams{}, params, name), seed);
  if (name == "irregular") return irregular_city(overlaid(IrregularParams{}, params, name), seed);
  if (name == "thesis") return thesis_city(overlaid(ThesisParams{}, params, name), seed);
  if (name == "openings") return openings_city(overlaid(OpeningsParams{}, params, name), seed);
  if (name == "kept") return kept_city(overlaid(KeptParams{}, params, name));
  if (name == "slot_city") return slot_city(overlaid(SlotCityParams{}, params, name), seed);
  if (name == "star_block_city") return star_block_city(overlaid(StarBlockParams{}, params, name), seed);
  if (name == "detailed") return detailed_city(overlaid(DetailedCityParams{}, params, name), seed);
  unknown_generator(name);
}

std::optional<ManhattanParams> manhattan_params_of(const Scene& scene) {
  nlohmann::json stored;
  try {
    stored = nlohmann::json::parse(scene.provenance.parameters_json);
  } catch (const nlohmann::json::parse_error&) {
    throw InputError("scene", "provenance.parameters", "is not valid JSON");
  }
  if (scene.provenance.generator == "thesis") {
    ThesisParams t;
    overlay_params_json(t, stored, "scene", "provenance.parameters of generator thesis");
    return thesis_street_grid(t);
  }
  if (scene.provenance.generator == "openings") {
    // Its blocks stand on a Manhattan street grid; bridges pass over the streets above eye level.
    OpeningsParams o;
    overlay_params_json(o, stored, "scene", "provenance.parameters of generator openings");
    validate(o);
    ManhattanParams m;
    m.blocks_x = o.blocks_x, m.blocks_y = o.blocks_y, m.block_size = o.block_size, m.street_width = o.street_width;
    return m;
  }
  if (scene.provenance.generator == "detailed") {  // detailed meshes on a Manhattan layout
    DetailedCityParams d;
    overlay_params_json(d, stored, "scene", "provenance.parameters of generator detailed");
    validate(d);
    return d.layout;
  }
  std::optional<ManhattanParams> p = manhattan_defaults(scene.provenance.generator);
  if (!p) return std::nullopt;
  overlay_params_json(*p, stored, "scene", "provenance.parameters of generator " + scene.provenance.generator);
  validate(*p, scene.provenance.generator);
  return p;
}

std::optional<ManhattanParams> thesis_street_grid(const ThesisParams& t) {
  const int side = t.buildings_per_block_side;
  if (t.grid_x % side != 0 || t.grid_y % side != 0) return std::nullopt;
  // Both layouts centre the city on the origin and put one street width between blocks, so a
  // Manhattan grid of blocks as wide as a thesis block has the same street centre lines.
  ManhattanParams m;
  m.blocks_x = t.grid_x / side;
  m.blocks_y = t.grid_y / side;
  m.block_size = side * t.building_size + (side - 1) * t.building_gap;
  m.street_width = t.street_width;
  return m;
}

}  // namespace cullcheck::generators
