// The GeoJSON footprint reader (core/formats/footprint_formats.hpp: geojson_from_text), with
// storeys and metres, local and file-named CRSs. An accepted scene must hold the scene invariants
// and the import report must account for every feature.
#include "core/errors.hpp"
#include "core/formats/footprint_formats.hpp"
#include "fuzz/harness.hpp"
#include "fuzz/scene_invariants.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace cullcheck;
  const std::string text = fuzz::bytes_of(data, size);
  for (int variant = 0; variant < 2; ++variant) {
    fuzz::reject_only_as<InputError>([&] {
      formats::FootprintOptions options;
      if (variant == 0) {
        options.storeys_attribute = "floors";
        options.missing_height = 3.0;
        options.crs = "local";
      } else {
        options.height_attribute = "height";  // the file's CRS, or WGS84 longitude/latitude
      }
      formats::ImportReport report;
      const Scene scene = formats::geojson_from_text(text, options, &report);
      fuzz::check_scene(scene);
      fuzz::require(report.buildings == scene.buildings.size(), "every building is counted");
      fuzz::require(report.buildings >= report.parts_split, "split parts are buildings");
      fuzz::require(report.features >= report.skipped_no_height + report.skipped_not_polygon, "skips are features");
    });
  }
  return 0;
}
