// cullcheck verify: methods held to the oracle for one camera or along a path; exit 1 when a
// method that claims to be conservative culled something the oracle saw.
#include <iostream>
#include <memory>

#include "apps/cullcheck/flags.hpp"
#include "apps/cullcheck/subcommands.hpp"
#include "core/scene_io.hpp"
#include "reports/report.hpp"
#include "reports/verification.hpp"

namespace cullcheck::cli {

Runner add_verify(CLI::App& app) {
  struct Flags {
    SceneFlags scene;
    PathFlags path;
    SamplingFlags sampling;
    MethodFlags tuning;
    RegionFlags regions;
    std::string methods = "all", camera;
  };
  auto f = std::make_shared<Flags>();
  CLI::App* sub = app.add_subcommand("verify", "Hold methods to the oracle for one camera or a path; exit 1 on a violation");
  f->scene.add(*sub);
  f->path.add(*sub, 60);
  f->sampling.add(*sub);
  f->tuning.add(*sub);
  sub->add_option("--method", f->methods, "Comma-separated methods, or 'all'")->capture_default_str();
  sub->add_option("--camera", f->camera, "One camera as JSON (instead of a path)");
  f->regions.add(*sub, "none");
  return [f] {
    const Scene scene = f->scene.source.load();
    const std::vector<std::string> methods = parse_methods(f->methods);
    CoordinateConversion coordinates;
    CameraPath path = f->path.load(scene, f->camera, &coordinates);
    VerificationOptions options;
    options.oracle.sampling = f->sampling.sampling;
    options.max_replays = 10;
    options.region_methods = parse_methods(f->regions.methods, region_method_names());
    options.region_radius = f->regions.radius;
    options.region_turn = f->regions.turn;
    options.region_on_tiling = f->regions.placement == "tiling";
    if (f->camera.empty()) options.path_replay_flags = f->path.replay_flags();
    const PathVerification v = verify_path(scene, f->scene.source, path, methods, f->tuning.options, options);
    std::cout << coordinates_line(coordinates, f->path.source_name(f->camera)) << "\n" << summary_table(v);
    for (const MethodRun& r : v.runs)
      for (const Violation& x : r.violations)
        std::cout << "violation: " << r.method << " culled building " << x.building << " at frame " << x.frame << " (oracle "
                  << x.model << (x.witness.empty() ? "" : ", witness " + x.witness) << ")\n  replay: " << x.replay << "\n";
    return conservative_violations(v) == 0 ? 0 : kExitGateFailed;
  };
}

}  // namespace cullcheck::cli
