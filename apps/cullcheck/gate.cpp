// cullcheck gate: the CI gate for any culling system. Outside subjects (a program over the
// subject protocol, or its recorded visible sets) and built-in methods meet the oracle along a
// path or at one camera; exit 1 when a conservative one missed what the oracle saw or an
// approximate one exceeded its pixel budget, exit 2 when a subject crashed, hung or lied (the
// report of the frames before it is written all the same).
#include <iostream>
#include <map>
#include <memory>

#include "apps/cullcheck/flags.hpp"
#include "apps/cullcheck/subject_flags.hpp"
#include "apps/cullcheck/subcommands.hpp"
#include "core/errors.hpp"
#include "core/scene_io.hpp"
#include "reports/gate_verdict.hpp"
#include "reports/junit.hpp"
#include "reports/report.hpp"
#include "reports/subject_claims.hpp"
#include "reports/verification.hpp"

namespace cullcheck::cli {

Runner add_gate(CLI::App& app) {
  struct Flags {
    SceneFlags scene;
    PathFlags path;
    SamplingFlags sampling;
    MethodFlags tuning;
    SubjectFlags subjects;
    std::string methods = "none", camera, output = "gate.json", junit;
    std::int64_t frame = -1;
    double max_overestimation = 0.0;
    std::size_t oracle_stride = 1;
    bool no_pixels = false, allow_empty_path = false, hold_conservative = false;
  };
  auto f = std::make_shared<Flags>();
  CLI::App* sub = app.add_subcommand(
      "gate", "The CI gate for any culling system: hold outside subjects (--subject PROGRAM over the subject protocol, "
              "--pvs FILE of recorded visible sets, --visible IDS for one camera) and built-in methods to the oracle; "
              "exit 1 on a miss or a pixel budget exceeded, 2 when a subject crashes, hangs or lies");
  f->scene.add(*sub);
  f->path.add(*sub, 60);
  f->sampling.add(*sub);
  f->tuning.add(*sub);
  f->subjects.add(*sub, /*inline_visible=*/true);
  sub->add_option("--method", f->methods, "Built-in methods to run beside them, comma-separated, 'all' or 'none'")
      ->capture_default_str();
  sub->add_option("--camera", f->camera, "One camera as JSON (instead of a path)");
  sub->add_option("--frame", f->frame, "Check only this frame of the path (replays name it)");
  sub->add_option("--oracle-stride", f->oracle_stride, "Check every n-th frame with the oracle")
      ->capture_default_str()
      ->check(CLI::Range(std::size_t(1), std::size_t(1) << 40));
  sub->add_flag("--hold-conservative", f->hold_conservative, "Judge every built-in method as claiming conservativeness, whatever it claims: how a paper's claim the engine does not gate is checked (e.g. rdt)");
  sub->add_flag("--no-pixels", f->no_pixels,
                "Skip the pixel oracle (misdrawn pixels) for subjects that claim conservativeness; approximate ones always get it");
  sub->add_option("--max-overestimation", f->max_overestimation,
                  "Also fail a method whose PVS / witnessed exceeds this (a culler that culls nothing passes the "
                  "conservative check)")
      ->check(CLI::Range(1.0, 1e9));
  sub->add_flag("--allow-empty-path", f->allow_empty_path,
                "Accept a path on which the oracle sees nothing (refused by default, exit 2: a culler that culls "
                "everything would pass it)");
  sub->add_option("--output,-o", f->output, "Report file to write (also when a subject fails)")->capture_default_str();
  sub->add_option("--junit", f->junit, "Also write the checks as JUnit XML (one test case per method and check)");
  return [f] {
    const Scene scene = f->scene.source.load();
    CoordinateConversion coordinates;
    CameraPath path = f->path.load(scene, f->camera, &coordinates);
    VerificationOptions options;
    options.oracle.sampling = f->sampling.sampling;
    options.oracle_stride = f->oracle_stride;
    options.max_replays = 10;
    options.pixels = !f->no_pixels;
    options.hold_conservative = f->hold_conservative;
    if (f->camera.empty()) options.path_replay_flags = f->path.replay_flags() + f->tuning.replay_flags();
    if (f->frame >= 0) {
      if (static_cast<std::size_t>(f->frame) >= path.frames.size())
        throw InputError("command line", "--frame", "is " + std::to_string(f->frame) + ", the path has " +
                                                        std::to_string(path.frames.size()) + " frames");
      path.frames = {path.frames[static_cast<std::size_t>(f->frame)]};
      options.first_frame = static_cast<std::size_t>(f->frame);
    }
    const std::string scene_flags = f->scene.source.replay_flags();
    const PathVerification v = f->subjects.verify(scene, f->scene.source, path, f->camera.empty() ? f->path.replay_flags() + f->tuning.replay_flags() : "",
                                                  parse_methods(f->methods), f->tuning.options, options, /*require_any=*/true);
    ReportInputs in;
    in.method_options = f->tuning.options;
    in.scene = &scene;
    in.source = f->scene.source;
    in.path = &path;
    in.path_parameters_json = f->path.file.empty() && f->camera.empty() ? f->path.params : "{}";
    in.coordinates = coordinates;
    in.verification = &v;
    in.claims = subject_claims(v);
    if (f->max_overestimation > 0.0) in.thresholds.max_overestimation = f->max_overestimation;
    // One camera, or one frame of a path, may rightly see nothing; a whole path must see something.
    in.thresholds.require_witnessed = f->camera.empty() && f->frame < 0 && !f->allow_empty_path;
    nlohmann::json document = build_report(in);
    const GateVerdict verdict = gate_verdict(v, scene_flags, in.thresholds);
    // Bytes that are not UTF-8 (a subject's garbage) are replaced rather than fail the report.
    write_text_file_atomically(f->output, document.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
    if (!f->junit.empty()) write_text_file_atomically(f->junit, junit_xml({verdict}));
    std::cout << coordinates_line(coordinates, f->path.source_name(f->camera)) << "\n" << summary_table(v);
    for (const MethodRun& r : v.runs) {
      for (const Violation& x : r.violations)
        std::cout << "violation: " << r.method << " culled object " << x.building << " at frame " << x.frame << " (oracle "
                  << x.model << (x.witness.empty() ? "" : ", witness " + x.witness) << ")\n  replay: " << x.replay << "\n";
      for (const Violation& x : r.over_budget)
        std::cout << "over budget: " << r.method << " at frame " << x.frame << ": " << x.witness << "\n  replay: " << x.replay << "\n";
    }
    // Violations count only after their witness ray stands re-cast in double precision.
    std::cout << "witness re-check (double precision): " << v.oracle.witness_recheck.checked << " checked, "
              << v.oracle.witness_recheck.dropped << " dropped\n";
    for (const MethodRun& r : v.runs)
      if (r.witness_recheck.checked > 0)
        std::cout << "  " << r.method << ": " << r.witness_recheck.checked << " checked, " << r.witness_recheck.dropped << " dropped\n";
    std::cout << "gate: " << (verdict.passed() ? "passed" : "FAILED") << "; wrote " << f->output << "\n";
    if (v.aborted) std::cerr << "cullcheck: " << v.aborted->message << "\n";
    for (const GateCheck& c : verdict.checks)
      if (c.check == "witnessed") std::cerr << "cullcheck: gate: " << c.message << " (--allow-empty-path accepts it)\n";
    return verdict.exit_code();
  };
}

}  // namespace cullcheck::cli
