// cullcheck gate: the CI gate for any culling system. Outside subjects (a program over the
// subject protocol, or its recorded visible sets) and built-in methods meet the oracle along a
// path or at one camera; exit 1 when a conservative one missed what the oracle saw or an
// approximate one exceeded its pixel budget, exit 2 when a subject crashed, hung or lied (the
// report of the frames before it is written all the same).
#include <iostream>
#include <map>
#include <memory>

#include "apps/cullcheck/flags.hpp"
#include "apps/cullcheck/subcommands.hpp"
#include "core/errors.hpp"
#include "core/scene_io.hpp"
#include "reports/gate_verdict.hpp"
#include "reports/junit.hpp"
#include "reports/report.hpp"
#include "reports/subject_claims.hpp"
#include "reports/verification.hpp"
#include "subjects/recorded_pvs.hpp"
#include "subjects/scene_files.hpp"
#include "subjects/subject_method.hpp"

namespace cullcheck::cli {
namespace {

std::string camera_text(const Camera& c) {
  std::string t = camera_to_json_text(c);
  if (!t.empty() && t.back() == '\n') t.pop_back();
  return shell_quote(t);
}

protocol::Claim claim_from_flags(const std::string& claims, std::int64_t budget) {
  protocol::Claim claim;
  if (claims == "approximate") {
    if (budget < 0) throw InputError("command line", "--pixel-budget", "an approximate claim needs a budget of misdrawn pixels per frame");
    claim.conservative = false;
    claim.pixel_error_budget = static_cast<std::uint64_t>(budget);
  } else if (budget >= 0) {
    throw InputError("command line", "--pixel-budget", "applies to --claims approximate only");
  }
  return claim;
}

}  // namespace

Runner add_gate(CLI::App& app) {
  struct Flags {
    SceneFlags scene;
    PathFlags path;
    SamplingFlags sampling;
    MethodFlags tuning;
    std::vector<std::string> subjects, pvs_files;
    std::string methods = "none", camera, visible, claims = "conservative", output = "gate.json", junit, work_dir;
    std::int64_t pixel_budget = -1;
    std::int64_t frame = -1;
    double frame_timeout = 10.0, hello_timeout = 60.0, max_overestimation = 0.0;
    std::size_t oracle_stride = 1;
    bool no_pixels = false, keep_work_dir = false;
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
  sub->add_option("--subject", f->subjects,
                  "An outside culling system: the command line of a program speaking the subject protocol on its "
                  "stdin/stdout (README), run by /bin/sh -c; repeat for several");
  sub->add_option("--pvs", f->pvs_files, "A file of recorded visible sets, one JSON line per frame (README); repeatable");
  sub->add_option("--visible", f->visible, "The visible set of one camera (--camera) as a JSON array of ids");
  sub->add_option("--claims", f->claims, "What --pvs files without a ready line and --visible claim: conservative or approximate")
      ->capture_default_str()
      ->check(CLI::IsMember({"conservative", "approximate"}));
  sub->add_option("--pixel-budget", f->pixel_budget, "With --claims approximate: misdrawn pixels allowed per frame");
  sub->add_option("--method", f->methods, "Built-in methods to run beside them, comma-separated, 'all' or 'none'")
      ->capture_default_str();
  sub->add_option("--camera", f->camera, "One camera as JSON (instead of a path)");
  sub->add_option("--frame", f->frame, "Check only this frame of the path (replays name it)");
  sub->add_option("--timeout", f->frame_timeout, "Seconds a subject may take to answer one frame")
      ->capture_default_str()
      ->check(CLI::Range(0.001, 86400.0));
  sub->add_option("--hello-timeout", f->hello_timeout, "Seconds a subject may take to load the scene and answer the hello")
      ->capture_default_str()
      ->check(CLI::Range(0.001, 86400.0));
  sub->add_option("--oracle-stride", f->oracle_stride, "Check every n-th frame with the oracle")
      ->capture_default_str()
      ->check(CLI::Range(std::size_t(1), std::size_t(1) << 40));
  sub->add_flag("--no-pixels", f->no_pixels,
                "Skip the pixel oracle (misdrawn pixels) for subjects that claim conservativeness; approximate ones always get it");
  sub->add_option("--max-overestimation", f->max_overestimation,
                  "Also fail a method whose PVS / witnessed exceeds this (a culler that culls nothing passes the "
                  "conservative check)")
      ->check(CLI::Range(1.0, 1e9));
  sub->add_option("--output,-o", f->output, "Report file to write (also when a subject fails)")->capture_default_str();
  sub->add_option("--junit", f->junit, "Also write the checks as JUnit XML (one test case per method and check)");
  sub->add_option("--work-dir", f->work_dir, "Folder for the scene files handed to subjects and their stderr (default: a "
                                             "temporary one, removed afterwards)");
  sub->add_flag("--keep-work-dir", f->keep_work_dir, "Keep the temporary folder (its path is printed)");
  return [f] {
    const Scene scene = f->scene.source.load();
    CameraPath path;
    if (!f->camera.empty()) {
      path.kind = "single_camera";
      path.frames.push_back(camera_from_json_text(f->camera));
    } else {
      if (!f->visible.empty()) throw InputError("command line", "--visible", "needs --camera (it is the visible set of one camera)");
      path = f->path.load(scene);
    }
    VerificationOptions options;
    options.oracle.sampling = f->sampling.sampling;
    options.oracle_stride = f->oracle_stride;
    options.max_replays = 10;
    options.pixels = !f->no_pixels;
    if (f->camera.empty()) options.path_replay_flags = f->path.replay_flags();
    if (f->frame >= 0) {
      if (static_cast<std::size_t>(f->frame) >= path.frames.size())
        throw InputError("command line", "--frame", "is " + std::to_string(f->frame) + ", the path has " +
                                                        std::to_string(path.frames.size()) + " frames");
      path.frames = {path.frames[static_cast<std::size_t>(f->frame)]};
      options.first_frame = static_cast<std::size_t>(f->frame);
    }
    const protocol::Claim flag_claim = claim_from_flags(f->claims, f->pixel_budget);
    std::vector<std::pair<std::string, std::string>> skipped;
    std::vector<MethodUnderTest> methods =
        builtin_methods(scene, f->scene.source, parse_methods(f->methods), f->tuning.options, options, &skipped);
    const std::string scene_flags = f->scene.source.replay_flags();
    const std::string claim_flags =
        f->claims == "approximate" ? " --claims approximate --pixel-budget " + std::to_string(f->pixel_budget) : "";
    for (const std::string& file : f->pvs_files) {
      MethodUnderTest m;
      m.method = std::make_unique<RecordedPvsMethod>(scene, file, flag_claim);
      m.outside = true;
      const std::string path_flags = f->camera.empty() ? " " + f->path.replay_flags() : " --camera " + camera_text(path.frames[0]);
      m.replay = [=](std::size_t frame, const Camera&) {
        return "cullcheck gate " + scene_flags + path_flags + " --pvs " + shell_quote(file) + claim_flags +
               (f->camera.empty() ? " --frame " + std::to_string(frame) : "");
      };
      methods.push_back(std::move(m));
    }
    if (!f->visible.empty()) {
      const nlohmann::json ids = parse_json_flag(f->visible, "visible");
      if (!ids.is_array()) throw InputError("command line", "--visible", "must be a JSON array of object ids");
      std::vector<ObjectId> given;
      for (const auto& id : ids) {
        if (!id.is_number_unsigned() || id.get<std::uint64_t>() > 0xFFFFFFFFULL)
          throw InputError("command line", "--visible", "holds " + id.dump() + ", not an object id");
        given.push_back(static_cast<ObjectId>(id.get<std::uint64_t>()));
      }
      MethodUnderTest m;
      m.method = std::make_unique<RecordedPvsMethod>(scene, std::map<std::size_t, std::vector<ObjectId>>{{0, given}}, flag_claim, "visible");
      m.outside = true;
      const std::string visible = f->visible;
      m.replay = [=](std::size_t, const Camera& camera) {
        return "cullcheck gate " + scene_flags + " --camera " + camera_text(camera) + " --visible " + shell_quote(visible) + claim_flags;
      };
      methods.push_back(std::move(m));
    }
    std::unique_ptr<WorkDir> work;
    protocol::SceneFiles files;
    PathVerification v;
    if (!f->subjects.empty()) {
      work = std::make_unique<WorkDir>(f->work_dir, f->keep_work_dir);
      if (f->keep_work_dir || !f->work_dir.empty()) std::cout << "work dir: " << work->path() << "\n";
      files = write_scene_files(scene, work->path());
    }
    for (std::size_t k = 0; k < f->subjects.size() && !v.aborted; ++k) {
      SubjectOptions so;
      so.command = f->subjects[k];
      so.files = files;
      so.stderr_path = work->file("subject-" + std::to_string(k) + ".stderr");
      so.frame_timeout = f->frame_timeout;
      so.hello_timeout = f->hello_timeout;
      try {
        MethodUnderTest m;
        m.method = std::make_unique<SubjectMethod>(scene, so, path.frames.size());
        m.outside = true;
        const std::string command = so.command;
        std::string timeouts;
        if (f->frame_timeout != 10.0) timeouts += " --timeout " + round_trip_text(f->frame_timeout);
        if (f->hello_timeout != 60.0) timeouts += " --hello-timeout " + round_trip_text(f->hello_timeout);
        // The subject is asked the failing frame alone, with its own index and time (a temporal
        // culler may depend on them): from the path when there is one, else the camera.
        const std::string path_flags = f->camera.empty() ? " " + f->path.replay_flags() : "";
        m.replay = [=](std::size_t frame, const Camera& camera) {
          return "cullcheck gate " + scene_flags + " --subject " + shell_quote(command) + timeouts +
                 (path_flags.empty() ? " --camera " + camera_text(camera) : path_flags + " --frame " + std::to_string(frame));
        };
        methods.push_back(std::move(m));
      } catch (const SubjectError& e) {
        v.aborted = Abort{"subject:" + program_name(so.command), SubjectError::kHandshake, SubjectError::kind_name(e.kind()), e.what()};
      }
    }
    if (methods.empty() && !v.aborted)
      throw InputError("command line", "--subject", "nothing to check: give --subject, --pvs, --visible or --method");
    if (!v.aborted) {
      v = verify_path(scene, f->scene.source, path, methods, f->tuning.options, options);
    }
    for (auto& s : skipped) v.skipped_methods.push_back(s);
    methods.clear();  // subjects say bye and exit here, before the report is written
    ReportInputs in;
    in.method_options = f->tuning.options;
    in.scene = &scene;
    in.source = f->scene.source;
    in.path = &path;
    in.path_parameters_json = f->path.file.empty() && f->camera.empty() ? f->path.params : "{}";
    in.verification = &v;
    in.claims = subject_claims(v);
    if (f->max_overestimation > 0.0) in.thresholds.max_overestimation = f->max_overestimation;
    nlohmann::json document = build_report(in);
    const GateVerdict verdict = gate_verdict(v, scene_flags, in.thresholds);
    write_text_file_atomically(f->output, document.dump(2) + "\n");
    if (!f->junit.empty()) write_text_file_atomically(f->junit, junit_xml({verdict}));
    std::cout << summary_table(v);
    for (const auto& [name, why] : v.skipped_methods) std::cout << "skipped " << name << ": " << why << "\n";
    for (const MethodRun& r : v.runs) {
      if (r.frames_skipped > 0) std::cout << r.method << ": " << r.frames_skipped << " frames skipped: " << r.skip_reason << "\n";
      for (const Violation& x : r.violations)
        std::cout << "violation: " << r.method << " culled object " << x.building << " at frame " << x.frame << " (oracle "
                  << x.model << (x.witness.empty() ? "" : ", witness " + x.witness) << ")\n  replay: " << x.replay << "\n";
      for (const Violation& x : r.over_budget)
        std::cout << "over budget: " << r.method << " at frame " << x.frame << ": " << x.witness << "\n  replay: " << x.replay << "\n";
    }
    std::cout << "gate: " << (verdict.passed() ? "passed" : "FAILED") << "; wrote " << f->output << "\n";
    if (v.aborted) std::cerr << "cullcheck: " << v.aborted->message << "\n";
    return verdict.exit_code();
  };
}

}  // namespace cullcheck::cli
