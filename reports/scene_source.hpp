// Where a run's scene comes from: a named generator with seed and parameters, or a scene file
// (scene JSON, glTF .glb/.gltf or OBJ: core/formats/mesh_formats.hpp; GeoJSON footprints:
// core/formats/footprint_formats.hpp). It rebuilds the scene and
// prints the command-line flags that rebuild it, which every replay line carries.
#pragma once

#include <cstdint>
#include <string>

#include "core/formats/mesh_formats.hpp"
#include "core/replay_text.hpp"
#include "core/scene.hpp"

namespace cullcheck {

struct SceneSource {
  std::string generator = "default";
  std::uint64_t seed = 1;
  std::string parameters_json = "{}";  // overlaid on the generator's defaults
  std::string file;                    // when set, the scene is read from this file instead
  // How a mesh file's objects are read (formats::ImportOptions; --mesh-ids node|mesh, --obj-up y|z).
  formats::IdSource mesh_ids = formats::IdSource::node;
  formats::UpAxis obj_up = formats::UpAxis::z;
  // How a footprint file's heights and CRS are read (--height-attribute, --storeys-attribute,
  // --storey-height, --missing-height, --crs).
  formats::FootprintOptions footprints{};

  // `report`, when given, receives what the import of a scene file did (counts, CRS, notes).
  Scene load(formats::ImportReport* report = nullptr) const;
  // e.g. "--generator plaza --seed 7 --params '{\"blocks_x\":2}'", "--scene city.json" or
  // "--scene city.glb --mesh-ids mesh" (the import flags only when not the defaults)
  std::string replay_flags() const;
};


}  // namespace cullcheck
