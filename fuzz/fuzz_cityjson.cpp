// The CityJSON reader (core/formats/footprint_formats.hpp: cityjson_from_text), with heights from
// the geometry and from a named attribute. An accepted scene must hold the scene invariants and
// the import report must account for every city object.
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
      options.crs = "local";  // PROJ's database is not what is fuzzed here
      if (variant == 1) {
        options.height_attribute = "RelativeRidgeHeight";
        options.missing_height = 4.0;
      }
      formats::ImportReport report;
      const Scene scene = formats::cityjson_from_text(text, options, &report);
      fuzz::check_scene(scene);
      fuzz::require(report.buildings == scene.buildings.size(), "every building is counted");
      fuzz::require(report.features >= report.skipped_no_height + report.skipped_not_polygon, "skips are city objects");
    });
  }
  return 0;
}
