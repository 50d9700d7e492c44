#include "apps/cullcheck/subject_flags.hpp"

#include <iostream>
#include <map>

#include "core/errors.hpp"
#include "core/scene_io.hpp"
#include "subjects/recorded_pvs.hpp"
#include "subjects/subject_method.hpp"

namespace cullcheck::cli {
void SubjectFlags::add(CLI::App& app, bool inline_visible) {
  app.add_option("--subject", subjects,
                 "An outside culling system: the command line of a program speaking the subject protocol on its "
                 "stdin/stdout (README), run by /bin/sh -c; repeat for several");
  app.add_option("--pvs", pvs_files, "A file of recorded visible sets, one JSON line per frame (README); repeatable");
  app.add_option("--timeout", frame_timeout, "Seconds a subject may take to answer one frame")
      ->capture_default_str()
      ->check(CLI::Range(0.001, 86400.0));
  app.add_option("--hello-timeout", hello_timeout, "Seconds a subject may take to load the scene and answer the hello")
      ->capture_default_str()
      ->check(CLI::Range(0.001, 86400.0));
  app.add_option("--work-dir", work_dir,
                 "Folder for the scene files handed to subjects and their stderr (default: a temporary one, removed afterwards)");
  app.add_flag("--keep-work-dir", keep_work_dir, "Keep the temporary folder (its path is printed)");
  app.add_flag("--no-glb", no_glb,
               "Hand subjects the scene JSON only (the hello's glb is null): a 160,000-building .glb takes ~7 s to write");
  app.add_option("--claims", claims, "What --pvs files without a ready line (and --visible) claim: conservative or approximate")
      ->capture_default_str()
      ->check(CLI::IsMember({"conservative", "approximate"}));
  app.add_option("--pixel-budget", pixel_budget, "With --claims approximate: misdrawn pixels allowed per frame");
  if (inline_visible) app.add_option("--visible", visible, "The visible set of one camera (--camera) as a JSON array of ids");
}

void SubjectFlags::build(const Scene& scene, const SceneSource& source, const CameraPath& path, const std::string& path_flags,
                         std::vector<MethodUnderTest>& methods, std::optional<Abort>& aborted) {
  protocol::Claim flag_claim;
  if (claims == "approximate") {
    if (pixel_budget < 0) throw InputError("command line", "--pixel-budget", "an approximate claim needs a budget of misdrawn pixels per frame");
    flag_claim.conservative = false;
    flag_claim.pixel_error_budget = static_cast<std::uint64_t>(pixel_budget);
  } else if (pixel_budget >= 0) {
    throw InputError("command line", "--pixel-budget", "applies to --claims approximate only");
  }
  const std::string scene_flags = source.replay_flags();
  const std::string claim_flags = claims == "approximate" ? " --claims approximate --pixel-budget " + std::to_string(pixel_budget) : "";
  // A failure replays the failing frame alone, with its own index (a temporal culler may depend on
  // it): `--frame N` of the path when there is one, else the one camera.
  auto where = [path_flags](std::size_t frame, const Camera& camera) {
    return path_flags.empty() ? " --camera " + camera_arg(camera) : " " + path_flags + " --frame " + std::to_string(frame);
  };
  for (const std::string& file : pvs_files) {
    MethodUnderTest m;
    m.method = std::make_unique<RecordedPvsMethod>(scene, file, flag_claim);
    m.outside = true;
    m.replay = [=](std::size_t frame, const Camera& camera) {
      return "cullcheck gate " + scene_flags + where(frame, camera) + " --pvs " + shell_quote(file) + claim_flags;
    };
    methods.push_back(std::move(m));
  }
  if (!visible.empty()) {
    if (path.frames.size() != 1 || !path_flags.empty())
      throw InputError("command line", "--visible", "needs --camera (it is the visible set of one camera)");
    const nlohmann::json ids = parse_json_flag(visible, "visible");
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
    const std::string text = visible;
    m.replay = [=](std::size_t, const Camera& camera) {
      return "cullcheck gate " + scene_flags + " --camera " + camera_arg(camera) + " --visible " + shell_quote(text) + claim_flags;
    };
    methods.push_back(std::move(m));
  }
  if (subjects.empty()) return;
  work_ = std::make_unique<WorkDir>(work_dir, keep_work_dir);
  if (keep_work_dir || !work_dir.empty()) std::cout << "work dir: " << work_->path() << "\n";
  const protocol::SceneFiles files = write_scene_files(scene, work_->path(), "scene", !no_glb);
  std::string timeouts;
  if (frame_timeout != 10.0) timeouts += " --timeout " + round_trip_text(frame_timeout);
  if (hello_timeout != 60.0) timeouts += " --hello-timeout " + round_trip_text(hello_timeout);
  for (std::size_t k = 0; k < subjects.size() && !aborted; ++k) {
    SubjectOptions so;
    so.command = subjects[k];
    so.files = files;
    so.stderr_path = work_->file("subject-" + std::to_string(k) + ".stderr");
    so.frame_timeout = frame_timeout;
    so.hello_timeout = hello_timeout;
    try {
      MethodUnderTest m;
      m.method = std::make_unique<SubjectMethod>(scene, so, path.frames.size());
      m.outside = true;
      const std::string command = so.command;
      m.replay = [=](std::size_t frame, const Camera& camera) {
        return "cullcheck gate " + scene_flags + " --subject " + shell_quote(command) + timeouts + where(frame, camera);
      };
      methods.push_back(std::move(m));
    } catch (const SubjectError& e) {
      aborted = Abort{"subject:" + program_name(so.command), SubjectError::kHandshake, SubjectError::kind_name(e.kind()), e.what()};
    }
  }
}

PathVerification SubjectFlags::verify(const Scene& scene, const SceneSource& source, const CameraPath& path,
                                      const std::string& path_flags, const std::vector<std::string>& builtin,
                                      const MethodOptions& method_options, const VerificationOptions& options, bool require_any) {
  std::vector<std::pair<std::string, std::string>> skipped;
  std::vector<MethodUnderTest> methods = builtin_methods(scene, source, builtin, method_options, options, &skipped);
  std::optional<Abort> aborted;
  build(scene, source, path, path_flags, methods, aborted);
  if (require_any && methods.empty() && !aborted)
    throw InputError("command line", "--subject", "nothing to check: give --subject, --pvs, --visible or --method");
  PathVerification v;
  if (aborted) v.aborted = aborted;
  else v = verify_path(scene, source, path, methods, method_options, options);
  v.skipped_methods.insert(v.skipped_methods.begin(), skipped.begin(), skipped.end());
  return v;  // `methods` goes out of scope first: the subjects say bye and exit
}

}  // namespace cullcheck::cli
