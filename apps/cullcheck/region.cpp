// cullcheck region: a from-region method's PVS for the disc around a camera; with --from, held to
// the oracle at that viewpoint.
#include <iostream>
#include <memory>
#include <optional>

#include "apps/cullcheck/flags.hpp"
#include "apps/cullcheck/subcommands.hpp"
#include "core/errors.hpp"
#include "core/scene_io.hpp"

namespace cullcheck::cli {

Runner add_region(CLI::App& app) {
  struct Flags {
    SceneFlags scene;
    MethodFlags tuning;
    SamplingFlags sampling;
    CoordinateFlags coordinates;
    std::string method = "shrink_adjustable_conservative", camera, from;
    double radius = 1.4142135623730951, turn = 0.0;
  };
  auto f = std::make_shared<Flags>();
  CLI::App* sub = app.add_subcommand(
      "region", "PVS of a from-region method for the disc around a camera; with --from, hold it to the oracle there");
  f->scene.add(*sub);
  f->tuning.add(*sub);
  f->sampling.add(*sub);
  sub->add_option("--method", f->method, "From-region method")->capture_default_str();
  sub->add_option("--camera", f->camera, "The region's centre camera as JSON")->required();
  sub->add_option("--radius", f->radius, "Disc radius (m)")->capture_default_str()->check(CLI::Range(0.0, 1e4));
  sub->add_option("--turn", f->turn, "Turn (rad) allowed")->capture_default_str()->check(CLI::Range(0.0, 1.5));
  sub->add_option("--from", f->from, "A viewpoint (camera JSON) of the region to check with the oracle");
  f->coordinates.add(*sub, "--camera and --from");
  return [f] {
    const Scene scene = f->scene.source.load();
    auto method = make_region_method(f->method, scene, f->tuning.options);
    const ViewRegion view_region{f->coordinates.camera(scene, f->camera, "--camera"), f->radius, f->turn};
    std::optional<Camera> from;
    if (!f->from.empty()) from = f->coordinates.camera(scene, f->from, "--from");
    if (view_region.camera.orthographic())
      throw InputError("camera", "projection", "a from-region PVS is for the eyes of a disc: give a perspective or 360-degree camera");
    const CullResult r = method->cull_region(view_region);
    nlohmann::json out = pvs_json(r);
    out["method"] = f->method;
    out["radius"] = f->radius;
    out["turn"] = f->turn;
    const int exit_code = check_from(scene, from, f->sampling.sampling, r.pvs, *method, out);
    std::cout << out.dump() << "\n";
    return exit_code;
  };
}

}  // namespace cullcheck::cli
