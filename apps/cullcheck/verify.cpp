// cullcheck verify: methods held to the oracle for one camera or along a path; exit 1 when a
// method that claims to be conservative culled something the oracle saw.
#include <iostream>
#include <memory>

#include "apps/cullcheck/flags.hpp"
#include "apps/cullcheck/subcommands.hpp"
#include "core/scene_io.hpp"
#include "core/errors.hpp"
#include "reports/report.hpp"
#include "reports/report_parts.hpp"
#include "reports/verification.hpp"

namespace cullcheck::cli {

Runner add_verify(CLI::App& app) {
  struct Flags {
    SceneFlags scene;
    PathFlags path;
    SamplingFlags sampling;
    MethodFlags tuning;
    RegionFlags regions;
    std::string methods = "all", camera, output;
    Shard shard;
    bool hold_conservative = false;
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
  sub->add_flag("--hold-conservative", f->hold_conservative, "Judge every built-in method as claiming conservativeness, whatever it claims: how a paper's claim the engine does not gate is checked (e.g. rdt)");
  sub->add_option("--output,-o", f->output, "Also write the results as report.json (no claims ledger or sections)");
  add_shard_flag(*sub, f->shard,
                 "Check shard K of N (e.g. 0/4) of the frames: the n-th frame is shard n mod N's (every shard runs the methods "
                 "along the whole path); needs --output, and `cullcheck merge` joins the N files");
  return [f] {
    if (!f->shard.whole() && f->output.empty()) throw InputError("flag", "shard", "needs --output: the file `cullcheck merge` joins");
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
    if (f->camera.empty()) options.path_replay_flags = f->path.replay_flags() + f->tuning.replay_flags();
    options.shard = f->shard;
    options.hold_conservative = f->hold_conservative;
    ReportParts parts;
    parts.verification = verify_path(scene, f->scene.source, path, methods, f->tuning.options, options);
    const PathVerification& v = parts.verification;
    if (!f->output.empty()) {
      ReportInputs in;
      in.scene = &scene;
      in.source = f->scene.source;
      in.path = &path;
      in.path_parameters_json = f->path.file.empty() && f->camera.empty() ? f->path.params : "{}";
      in.coordinates = coordinates;
      in.path_replay_flags = f->camera.empty() ? f->path.replay_flags() + f->tuning.replay_flags() : "--camera '" + f->camera + "'";
      parts.header = report_header(in);
      parts.method_options = f->tuning.options;
      nlohmann::json density;
      oracle::to_json(density, options.oracle.sampling);
      parts.identity = {{"methods", f->methods}, {"density", density}, {"regions", {f->regions.methods, f->regions.radius, f->regions.turn, f->regions.placement}}, {"max_replays", options.max_replays}};
      nlohmann::json document = assemble_report(parts).document;
      if (!f->shard.whole()) document = shard_document(std::move(document), parts, f->shard);
      write_text_file_atomically(f->output, document.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
    }
    std::cout << coordinates_line(coordinates, f->path.source_name(f->camera)) << "\n" << summary_table(v);
    for (const MethodRun& r : v.runs)
      for (const Violation& x : r.violations)
        std::cout << "violation: " << r.method << " culled building " << x.building << " at frame " << x.frame << " (oracle "
                  << x.model << (x.witness.empty() ? "" : ", witness " + x.witness) << ")\n  replay: " << x.replay << "\n";
    if (!f->output.empty()) std::cout << "wrote " << f->output << (f->shard.whole() ? "" : " (shard " + f->shard.text() + ")") << "\n";
    return conservative_violations(v) == 0 ? 0 : kExitGateFailed;
  };
}

}  // namespace cullcheck::cli
