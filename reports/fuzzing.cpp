#include "reports/fuzzing.hpp"

#include <rapidcheck.h>

#include <chrono>
#include <iostream>
#include <sstream>
#include <filesystem>
#include <fstream>

#include "core/errors.hpp"
#include "core/scene_io.hpp"
#include "reports/frame_pictures.hpp"
#include "reports/gate_verdict.hpp"
#include "subjects/scene_files.hpp"
#include "subjects/subject_error.hpp"
#include "subjects/subject_method.hpp"

namespace cullcheck {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

struct CaseOutcome {
  bool failed = false;
  bool subject_error = false;
  std::string message;
  PathVerification verification;
  std::map<std::size_t, std::vector<ObjectId>> pvs_by_frame;
  std::size_t objects = 0, triangles = 0;  // the case's scene
};

// Forwards to the subject and keeps each frame's answer, for the counterexample's pictures.
class Recording final : public CullingMethod {
 public:
  Recording(std::unique_ptr<CullingMethod> inner, std::map<std::size_t, std::vector<ObjectId>>& out)
      : inner_(std::move(inner)), out_(out) {}
  std::string name() const override { return inner_->name(); }
  bool claims_conservative() const override { return inner_->claims_conservative(); }
  std::optional<std::uint64_t> pixel_error_budget() const override { return inner_->pixel_error_budget(); }
  std::string unsupported_camera(const Camera& c) const override { return inner_->unsupported_camera(c); }
  void set_frame(std::size_t frame, double time) override {
    frame_ = frame;
    inner_->set_frame(frame, time);
  }
  CullResult cull(const Camera& camera) override {
    CullResult r = inner_->cull(camera);
    out_[frame_] = r.pvs;
    return r;
  }

 private:
  std::unique_ptr<CullingMethod> inner_;
  std::map<std::size_t, std::vector<ObjectId>>& out_;
  std::size_t frame_ = 0;
};

// One case: a fresh run of the subject on the case's scene and path, held to the oracle.
CaseOutcome run_case(const generators::FuzzCase& c, const FuzzOptions& options, const std::string& dir) {
  CaseOutcome out;
  const Scene scene = generators::scene_of(c.spec);
  out.objects = scene.object_count();
  out.triangles = scene.triangle_count();
  SubjectOptions so;
  so.command = options.subject;
  so.files = write_scene_files(scene, dir);
  so.stderr_path = dir + "/subject.stderr";
  so.frame_timeout = options.frame_timeout;
  so.hello_timeout = options.hello_timeout;
  so.exit_timeout = 1.0;
  VerificationOptions vo;
  vo.oracle.sampling = options.sampling;
  vo.max_replays = 5;
  vo.pixels = options.pixels;
  const SceneSource source{c.spec.generator, c.spec.seed, c.spec.params.dump(), ""};
  std::vector<MethodUnderTest> methods;
  try {
    MethodUnderTest m;
    m.method = std::make_unique<Recording>(std::make_unique<SubjectMethod>(scene, so, c.path.frames.size()), out.pvs_by_frame);
    m.outside = true;
    m.replay = [source, command = options.subject](std::size_t, const Camera& camera) {
      return "cullcheck gate " + source.replay_flags() + " --subject " + shell_quote(command) + " --camera " + camera_arg(camera);
    };
    methods.push_back(std::move(m));
    out.verification = verify_path(scene, source, c.path, methods, {}, vo);
  } catch (const SubjectError& e) {
    out.verification.aborted = Abort{"subject", e.frame(), SubjectError::kind_name(e.kind()), e.what()};
  }
  methods.clear();
  const GateVerdict verdict = gate_verdict(out.verification, source.replay_flags());
  out.failed = !verdict.passed() || out.verification.aborted.has_value();
  out.subject_error = out.verification.aborted.has_value();
  for (const GateCheck& check : verdict.checks) {
    if (check.outcome != GateCheck::Outcome::failed && check.outcome != GateCheck::Outcome::error) continue;
    out.message += (out.message.empty() ? "" : "; ") + check.check + ": " + check.message;
  }
  if (out.verification.aborted && out.message.find(out.verification.aborted->message) == std::string::npos)
    out.message += (out.message.empty() ? "" : "; ") + out.verification.aborted->message;
  return out;
}

}  // namespace

FuzzResult fuzz_subject(const FuzzOptions& options) {
  const auto start = Clock::now();
  FuzzResult result;
  WorkDir work(options.work_dir);
  {  // The handshake on a one-building scene tells what the subject takes.
    Scene probe;
    probe.buildings.push_back(box_building(0, -5, -5, 5, 5, 10));
    SubjectOptions so;
    so.command = options.subject;
    so.files = write_scene_files(probe, work.path(), "probe");
    so.stderr_path = work.file("probe.stderr");
    so.hello_timeout = options.hello_timeout;
    so.exit_timeout = 1.0;
    const SubjectMethod subject(probe, so, 0);
    result.ready = subject.ready();
    result.subject_name = subject.name();
  }
  const auto gen = generators::rcgen::fuzz_case(generators::rcgen::fuzz_scene_spec(), result.ready.orthographic);
  bool failing = false;
  auto property = [&] {
    const generators::FuzzCase c = *gen;
    if (failing) ++result.shrink_runs;
    else ++result.cases, ++result.kinds[c.kind], ++result.scenes[c.spec.generator];
    CaseOutcome outcome = run_case(c, options, work.path());
    if (!outcome.failed) return;
    const bool first = !failing;
    if (first) result.seconds_to_failure = seconds_since(start);
    failing = true;
    // Shrinking accepts a smaller case only when it fails too, so the last failing case seen is
    // the minimal one RapidCheck reports.
    result.failure = FuzzFailure{c,
                                 outcome.message,
                                 outcome.subject_error,
                                 std::move(outcome.verification),
                                 std::move(outcome.pvs_by_frame),
                                 outcome.objects,
                                 outcome.triangles,
                                 first ? outcome.objects : result.failure->first_objects,
                                 first ? c.path.frames.size() : result.failure->first_frames};
    RC_FAIL(outcome.message);
  };
  // A listener of our own: RapidCheck's default one reads RC_PARAMS and prints its own seed,
  // which would be the wrong replay for a run seeded by --seed.
  struct Quiet final : rc::detail::TestListener {
    int accepted_shrinks = 0;
    void onTestCaseFinished(const rc::detail::CaseDescription&) override {}
    void onShrinkTried(const rc::detail::CaseDescription&, bool accepted) override { accepted_shrinks += accepted; }
    void onTestFinished(const rc::detail::TestMetadata&, const rc::detail::TestResult&) override {}
  } listener;
  // RapidCheck loads its global configuration (RC_PARAMS) on first use and prints the seed it
  // picked to std::cerr; our cases are seeded by options.seed alone, so that line would name a
  // seed that replays nothing. Load it once with std::cerr silenced.
  {
    std::ostringstream silenced;
    std::streambuf* saved = std::cerr.rdbuf(silenced.rdbuf());
    try {
      rc::detail::configuration();
    } catch (...) {
      std::cerr.rdbuf(saved);
      throw;
    }
    std::cerr.rdbuf(saved);
  }
  rc::detail::TestParams params;
  params.seed = options.seed;
  params.maxSuccess = options.budget;
  params.maxSize = 100;
  params.maxDiscardRatio = 10;
  const rc::detail::TestResult tested =
      rc::detail::checkProperty(rc::detail::toProperty(property), rc::detail::TestMetadata{}, params, listener);
  result.shrinks_accepted = listener.accepted_shrinks;
  if (tested.is<rc::detail::Error>()) throw std::runtime_error("RapidCheck: " + tested.get<rc::detail::Error>().description);
  result.seconds_total = seconds_since(start);
  return result;
}

nlohmann::json fuzz_json(const FuzzResult& r) {
  nlohmann::json j = {{"subject", r.subject_name},
                      {"claims", r.ready.claim.conservative ? "conservative" : "approximate"},
                      {"cases", r.cases},
                      {"shrink_runs", r.shrink_runs},
                      {"shrinks_accepted", r.shrinks_accepted},
                      {"seconds_to_failure", r.failure ? nlohmann::json(r.seconds_to_failure) : nlohmann::json(nullptr)},
                      {"seconds_total", r.seconds_total},
                      {"cases_by_path_kind", r.kinds},
                      {"cases_by_scene_generator", r.scenes}};
  if (r.ready.claim.pixel_error_budget) j["pixel_error_budget"] = *r.ready.claim.pixel_error_budget;
  if (r.failure) {
    const FuzzFailure& f = *r.failure;
    j["failure"] = {{"message", f.message},
                    {"subject_error", f.subject_error},
                    {"scene", {{"generator", f.minimal.spec.generator}, {"seed", f.minimal.spec.seed}, {"parameters", f.minimal.spec.params}}},
                    {"objects", f.objects},
                    {"triangles", f.triangles},
                    {"first_failure_objects", f.first_objects},
                    {"first_failure_frames", f.first_frames},
                    {"path_kind", f.minimal.kind},
                    {"frames", f.minimal.path.frames.size()}};
  }
  return j;
}

std::string fuzz_summary(const FuzzResult& r, const std::string& dir) {
  std::ostringstream out;
  out << "fuzz " << r.subject_name << " (" << (r.ready.claim.conservative ? "conservative" : "approximate") << "): " << r.cases
      << " cases";
  const char* sep = " (";
  for (const auto& [kind, n] : r.kinds) out << sep << kind << " " << n, sep = ", ";
  out << (r.kinds.empty() ? "" : ")") << "\n";
  if (!r.failure) {
    out << "passed " << r.cases << " cases in " << r.seconds_total << " s\n";
    return out.str();
  }
  const FuzzFailure& f = *r.failure;
  out << "FAILED after " << r.cases << " cases (" << r.seconds_to_failure << " s); shrunk in " << r.shrink_runs << " more runs ("
      << r.shrinks_accepted << " accepted) from " << f.first_objects << " objects and " << f.first_frames << " frames to "
      << f.objects << " objects, " << f.triangles << " triangles, "
      << f.minimal.path.frames.size() << " frames (" << f.minimal.kind << ")\n"
      << "  " << f.message << "\n"
      << "  counterexample: " << dir << "/ (replay: sh " << dir << "/replay.sh)\n";
  return out.str();
}

ClaimCheck fuzz_claim(const FuzzResult& r, const std::string& replay) {
  ClaimCheck c;
  c.method = r.subject_name;
  c.source = "declared by the subject, fuzzed (cullcheck fuzz)";
  if (r.ready.claim.conservative) {
    c.id = r.subject_name + "-conservative-fuzzed";
    c.statement = "never culls an object the oracle sees, on any generated scene and pathological camera path";
  } else {
    c.id = r.subject_name + "-pixel-budget-fuzzed";
    c.statement = "misdraws at most " + std::to_string(r.ready.claim.pixel_error_budget.value_or(0)) +
                  " pixels in any frame, on any generated scene and pathological camera path";
  }
  c.frames_checked = static_cast<std::uint64_t>(r.cases);
  c.holds = !r.failure;
  c.search_seconds = r.failure ? r.seconds_to_failure : r.seconds_total;
  if (r.failure) {
    c.violations = 1;
    c.counterexample_replay = replay;
    c.counterexample_detail = r.failure->message + " (shrunk to " + std::to_string(r.failure->objects) + " objects, " +
                              std::to_string(r.failure->minimal.path.frames.size()) + " frames, " + r.failure->minimal.kind + ")";
  }
  return c;
}

std::string write_counterexample(const FuzzResult& result, const FuzzOptions& options, const std::string& dir) {
  namespace fs = std::filesystem;
  if (!result.failure) return "";
  const FuzzFailure& f = *result.failure;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw InputError("folder " + dir, "(folder)", "cannot be created: " + ec.message());
  const Scene scene = generators::scene_of(f.minimal.spec);
  write_scene_files(scene, dir);
  write_text_file_atomically(dir + "/path.json", path_to_json_text(f.minimal.path));
  if (f.minimal.path.frames.size() == 1) write_text_file_atomically(dir + "/camera.json", camera_to_json_text(f.minimal.path.frames[0]));
  const std::string replay = "cullcheck gate --scene \"$here/scene.json\" --path \"$here/path.json\" --subject " +
                             shell_quote(options.subject) + " --oracle-stride 1 -o \"$here/gate.json\"";
  write_text_file_atomically(dir + "/replay.sh", "#!/bin/sh\n# Replays the fuzzer's minimal counterexample: " + f.message +
                                                     "\nhere=$(cd \"$(dirname \"$0\")\" && pwd)\n" + replay + "\n");
  fs::permissions(dir + "/replay.sh", fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec, fs::perm_options::add, ec);
  nlohmann::json doc = fuzz_json(result);
  // The ledger's replay names the folder itself (replay.sh finds its files wherever it is moved).
  const std::string here = fs::absolute(dir).string();
  const std::string replay_here = "cullcheck gate --scene " + shell_quote(here + "/scene.json") + " --path " +
                                  shell_quote(here + "/path.json") + " --subject " + shell_quote(options.subject);
  doc["replay"] = replay_here;
  doc["generator_replay"] = "cullcheck gate " + generators::replay_args(f.minimal.spec) + " --path path.json --subject " +
                            shell_quote(options.subject);
  // The pictures of the first failing frame (none when the subject failed before answering one).
  std::optional<std::size_t> frame;
  if (!f.verification.runs.empty()) {
    const MethodRun& run = f.verification.runs.front();
    if (!run.violations.empty()) frame = run.violations.front().frame;
    else if (!run.over_budget.empty()) frame = run.over_budget.front().frame;
  }
  if (frame && frame < f.minimal.path.frames.size() && f.pvs_by_frame.count(*frame)) {
    oracle::OracleOptions oracle_options;
    oracle_options.sampling = options.sampling;
    const FramePictures pictures =
        write_frame_pictures(scene, f.minimal.path.frames[*frame], f.pvs_by_frame.at(*frame), oracle_options, dir);
    doc["pictures"] = {{"frame", *frame}, {"map", "map.png"}, {"image", "frame.png"}, {"missed", pictures.missed},
                       {"misdrawn_pixels", pictures.misdrawn_pixels}};
  }
  write_text_file_atomically(dir + "/case.json", doc.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
  return replay_here;
}

}  // namespace cullcheck
