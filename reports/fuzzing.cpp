#include "reports/fuzzing.hpp"
#include "core/progress.hpp"

#include <rapidcheck.h>

#include <algorithm>
#include <chrono>
#include <iostream>
#include <sstream>
#include <filesystem>
#include <fstream>

#include "core/elapsed.hpp"
#include "core/errors.hpp"
#include "core/scene_io.hpp"
#include "reports/frame_pictures.hpp"
#include "reports/gate_verdict.hpp"
#include "reports/shard_merge.hpp"
#include "subjects/scene_files.hpp"
#include "subjects/subject_error.hpp"
#include "subjects/subject_method.hpp"

namespace cullcheck {
namespace {

using Clock = std::chrono::steady_clock;

struct CaseOutcome {
  bool failed = false;
  bool subject_error = false;
  std::string message;
  std::string failed_method;
  PathVerification verification;
  std::map<std::string, std::map<std::size_t, std::vector<ObjectId>>> pvs_by_frame;  // by method
  std::vector<std::string> unavailable;    // built-in methods that cannot run on the case's scene
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

// A built-in method held to conservativeness whatever it claims is replayed so.
std::string held_flag(const FuzzOptions& options) { return options.hold_conservative ? " --hold-conservative" : ""; }

// The replay of one frame of a case: `cullcheck gate` with the subject or the built-in method.
std::string gate_replay(const SceneSource& source, const FuzzOptions& options, const std::string& method, const Camera& camera) {
  const std::string who = options.subject.empty() ? " --method " + method + held_flag(options) : " --subject " + shell_quote(options.subject);
  return "cullcheck gate " + source.replay_flags() + who + " --camera " + camera_arg(camera);
}

// One case: a fresh run of the subject (or fresh built-in methods) on the case's scene and path,
// held to the oracle.
CaseOutcome run_case(const generators::FuzzCase& c, const FuzzOptions& options, const std::string& dir) {
  CaseOutcome out;
  const Scene scene = generators::scene_of(c.spec);
  out.objects = scene.object_count();
  out.triangles = scene.triangle_count();
  VerificationOptions vo;
  vo.oracle.sampling = options.sampling;
  vo.max_replays = 5;
  vo.pixels = options.pixels;
  vo.reference_method.clear();  // the fuzzer judges each method by its own claim alone
  vo.measure_bare_embree = false;
  vo.hold_conservative = options.hold_conservative;
  const SceneSource source{c.spec.generator, c.spec.seed, c.spec.params.dump(), ""};
  std::vector<MethodUnderTest> methods;
  std::vector<std::string> names;
  try {
    if (options.subject.empty()) {
      std::vector<std::pair<std::string, std::string>> skipped;
      methods = builtin_methods(scene, source, options.methods, MethodOptions{}, vo, &skipped);
      for (const auto& [name, why] : skipped) out.unavailable.push_back(name);
    } else {
      SubjectOptions so;
      so.command = options.subject;
      so.files = write_scene_files(scene, dir);
      so.stderr_path = dir + "/subject.stderr";
      so.frame_timeout = options.frame_timeout;
      so.hello_timeout = options.hello_timeout;
      so.exit_timeout = 1.0;
      MethodUnderTest m;
      m.method = std::make_unique<SubjectMethod>(scene, so, c.path.frames.size());
      m.outside = true;
      methods.push_back(std::move(m));
    }
    for (MethodUnderTest& m : methods) {
      const std::string name = m.method->name();
      names.push_back(name);
      m.method = std::make_unique<Recording>(std::move(m.method), out.pvs_by_frame[name]);
      m.replay = [source, &options, name](std::size_t, const Camera& camera) { return gate_replay(source, options, name, camera); };
    }
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
    if (out.failed_method.empty()) out.failed_method = check.method;
  }
  if (out.verification.aborted && out.message.find(out.verification.aborted->message) == std::string::npos)
    out.message += (out.message.empty() ? "" : "; ") + out.verification.aborted->message;
  if (out.failed_method.empty() && !names.empty()) out.failed_method = names.front();
  return out;
}

// A one-building scene: what a subject's handshake and a method's claim are asked on.
Scene probe_scene() {
  Scene probe;
  probe.buildings.push_back(box_building(0, -5, -5, 5, 5, 10));
  return probe;
}

// The ledger's detail of the shrunk counterexample.
std::string counterexample_detail(const FuzzFailure& f) {
  return f.message + " (shrunk to " + std::to_string(f.objects) + " objects, " + std::to_string(f.minimal.path.frames.size()) +
         " frames, " + f.minimal.kind + ")";
}

}  // namespace

std::vector<std::string> conservative_method_names() {
  // A claim does not depend on the scene: ask each method built on a one-building probe.
  const Scene probe = probe_scene();
  std::vector<std::string> out;
  for (const std::string& name : method_names())
    if (make_method(name, probe)->claims_conservative()) out.push_back(name);
  return out;
}

FuzzResult fuzz_subject(const FuzzOptions& options) {
  const auto start = Clock::now();
  FuzzResult result;
  WorkDir work(options.work_dir);
  if (options.subject.empty()) {
    // Built-in methods: every kind of camera (a horizon method skips orthographic frames itself,
    // and they are counted), each judged by its own claim.
    if (options.methods.empty()) throw InputError("fuzz", "--method", "names no method (and no --subject was given)");
    const std::vector<std::string> known = method_names();
    for (const std::string& name : options.methods)
      if (std::find(known.begin(), known.end(), name) == known.end())
        throw InputError("fuzz", "--method", "unknown method '" + name + "'");
    result.ready.orthographic = true;
    result.ready.claim.conservative = true;
    result.built_in = true;
    result.held_conservative = options.hold_conservative;
    result.methods = options.methods;
    for (std::size_t i = 0; i < options.methods.size(); ++i) result.subject_name += (i ? "," : "") + options.methods[i];
  } else {  // The handshake on a one-building scene tells what the subject takes.
    const Scene probe = probe_scene();
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
  Progress progress("fuzzing " + result.subject_name, options.shard.share(static_cast<std::size_t>(options.budget)), "cases");
  std::int64_t drawn = 0;  // cases drawn so far (shrinking draws none)
  const bool sharded = !options.shard.whole();
  auto property = [&] {
    const generators::FuzzCase c = *gen;  // drawn in every shard: the next case is the same in all
    const std::int64_t index = failing ? -1 : drawn++;
    if (failing) ++result.shrink_runs;
    else if (!options.shard.owns(static_cast<std::size_t>(index))) return;  // another shard's case
    else ++result.kinds[c.kind], ++result.scenes[c.spec.generator], progress.advance();
    if (!failing) result.cases = static_cast<int>(drawn);
    CaseOutcome outcome = run_case(c, options, work.path());
    if (!failing) {
      nlohmann::json record = {{"case", index}, {"kind", c.kind}, {"scene", c.spec.generator},
                               {"oracle_frames", outcome.verification.oracle.frames_checked},
                               {"recheck", {outcome.verification.oracle.witness_recheck.checked, outcome.verification.oracle.witness_recheck.dropped}},
                               {"methods", nlohmann::json::object()}};
      result.oracle_frames += outcome.verification.oracle.frames_checked;
      result.witness_recheck += outcome.verification.oracle.witness_recheck;
      for (const MethodRun& run : outcome.verification.runs) {
        result.checked_frames[run.method] += run.checked_pvs_size.size();
        result.skipped_frames[run.method] += run.frames_skipped;
        result.witness_recheck_by_method[run.method] += run.witness_recheck;
        record["methods"][run.method] = {run.checked_pvs_size.size(), run.frames_skipped, run.witness_recheck.checked,
                                         run.witness_recheck.dropped, true};
      }
      for (const std::string& name : outcome.unavailable) {
        result.skipped_frames[name] += c.path.frames.size();
        nlohmann::json& m = record["methods"][name];
        if (m.is_null()) m = {0, 0, 0, 0, false};
        m[1] = m[1].get<std::uint64_t>() + c.path.frames.size();
      }
      if (sharded) result.per_case.push_back(std::move(record));
    }
    if (!outcome.failed) return;
    const bool first = !failing;
    if (first) result.seconds_to_failure = seconds_since(start), result.first_failing_case = index;
    failing = true;
    // Shrinking accepts a smaller case only when it fails too, so the last failing case seen is
    // the minimal one RapidCheck reports.
    auto& pvs = outcome.pvs_by_frame[outcome.failed_method];
    result.failure = FuzzFailure{c,
                                 outcome.failed_method,
                                 outcome.message,
                                 outcome.subject_error,
                                 std::move(outcome.verification),
                                 std::move(pvs),
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
  if (!result.failure) result.cases = static_cast<int>(drawn);
  if (tested.is<rc::detail::Error>()) throw std::runtime_error("RapidCheck: " + tested.get<rc::detail::Error>().description);
  result.seconds_total = seconds_since(start);
  return result;
}

nlohmann::json fuzz_json(const FuzzResult& r) {
  nlohmann::json j = {{"subject", r.subject_name},
                      {"claims", r.ready.claim.conservative ? "conservative" : "approximate"},
                      {"held_conservative", r.held_conservative},
                      {"cases", r.cases},
                      {"shrink_runs", r.shrink_runs},
                      {"shrinks_accepted", r.shrinks_accepted},
                      {"seconds_to_failure", r.failure ? nlohmann::json(r.seconds_to_failure) : nlohmann::json(nullptr)},
                      {"seconds_total", r.seconds_total},
                      {"cases_by_path_kind", r.kinds},
                      {"cases_by_scene_generator", r.scenes},
                      {"oracle_frames", r.oracle_frames},
                      {"checked_frames_by_method", r.checked_frames},
                      {"skipped_frames_by_method", r.skipped_frames}};
  nlohmann::json recheck = {{"checked", r.witness_recheck.checked}, {"dropped", r.witness_recheck.dropped}};
  for (const auto& [method, n] : r.witness_recheck_by_method)
    recheck["by_method"][method] = {{"checked", n.checked}, {"dropped", n.dropped}};
  j["witness_recheck"] = recheck;
  if (r.built_in) j["built_in_methods"] = r.methods;
  if (r.ready.claim.pixel_error_budget) j["pixel_error_budget"] = *r.ready.claim.pixel_error_budget;
  if (r.failure) {
    const FuzzFailure& f = *r.failure;
    j["failure"] = {{"method", f.method},
                    {"message", f.message},
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
  out << "oracle-checked frames (" << r.oracle_frames << " oracle answers):";
  sep = " ";
  for (const auto& [method, n] : r.checked_frames) {
    out << sep << method << " " << n;
    if (const auto skipped = r.skipped_frames.find(method); skipped != r.skipped_frames.end() && skipped->second > 0)
      out << " (" << skipped->second << " skipped)";
    sep = ", ";
  }
  out << "\n";
  out << "witness re-check (double precision): " << r.witness_recheck.checked << " checked, " << r.witness_recheck.dropped
      << " dropped\n";
  if (!r.failure) {
    out << "passed " << r.cases << " cases in " << r.seconds_total << " s\n";
    return out.str();
  }
  const FuzzFailure& f = *r.failure;
  out << "FAILED after " << r.cases << " cases (" << r.seconds_to_failure << " s); shrunk in " << r.shrink_runs << " more runs ("
      << r.shrinks_accepted << " accepted) from " << f.first_objects << " objects and " << f.first_frames << " frames to "
      << f.objects << " objects, " << f.triangles << " triangles, "
      << f.minimal.path.frames.size() << " frames (" << f.minimal.kind << ")\n"
      << "  " << f.method << ": " << f.message << "\n"
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
    c.counterexample_detail = counterexample_detail(*r.failure);
  }
  return c;
}

std::vector<ClaimCheck> fuzz_claims(const FuzzResult& r, const std::string& replay) {
  if (!r.built_in) return {fuzz_claim(r, replay)};
  std::vector<ClaimCheck> out;
  for (const std::string& method : r.methods) {
    ClaimCheck c;
    c.method = method;
    c.source = "cullcheck fuzz --method (built-in, in process)";
    c.id = method + "-conservative-fuzzed";
    c.statement = "never culls an object the oracle sees, on any generated scene and pathological camera path";
    const auto checked = r.checked_frames.find(method);
    c.frames_checked = checked == r.checked_frames.end() ? 0 : checked->second;
    const bool refuted = r.failure && r.failure->method == method;
    c.holds = !refuted;
    c.search_seconds = r.failure ? r.seconds_to_failure : r.seconds_total;
    if (refuted) {
      c.violations = 1;
      c.counterexample_replay = replay;
      c.counterexample_detail = counterexample_detail(*r.failure);
    }
    out.push_back(std::move(c));
  }
  return out;
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
  // The files say their frame (scene-local, and the origin it is local to), so a replay reads them
  // the same whatever --coordinates says.
  CameraPath path = f.minimal.path;
  path.coordinates = CoordinateFrame::local;
  path.origin = scene.origin;
  write_text_file_atomically(dir + "/path.json", path_to_json_text(path));
  if (path.frames.size() == 1) {
    nlohmann::json camera = nlohmann::json::parse(camera_to_json_text(path.frames[0]));
    camera["coordinates"] = "local";
    camera["origin"] = {scene.origin.x, scene.origin.y};
    write_text_file_atomically(dir + "/camera.json", camera.dump() + "\n");
  }
  const std::string who = options.subject.empty() ? "--method " + f.method + held_flag(options) : "--subject " + shell_quote(options.subject);
  const std::string replay = "cullcheck gate --scene \"$here/scene.json\" --path \"$here/path.json\" " + who +
                             " --oracle-stride 1 -o \"$here/gate.json\"";
  write_text_file_atomically(dir + "/replay.sh", "#!/bin/sh\n# Replays the fuzzer's minimal counterexample: " + f.message +
                                                     "\nhere=$(cd \"$(dirname \"$0\")\" && pwd)\n" + replay + "\n");
  fs::permissions(dir + "/replay.sh", fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec, fs::perm_options::add, ec);
  nlohmann::json doc = fuzz_json(result);
  // The ledger's replay names the folder itself (replay.sh finds its files wherever it is moved).
  const std::string here = fs::absolute(dir).string();
  const std::string replay_here = "cullcheck gate --scene " + shell_quote(here + "/scene.json") + " --path " +
                                  shell_quote(here + "/path.json") + " " + who;
  doc["replay"] = replay_here;
  doc["generator_replay"] = "cullcheck gate " + generators::replay_args(f.minimal.spec) + " --path path.json " + who;
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

namespace cullcheck {

nlohmann::json fuzz_shard_json(const FuzzResult& r, const FuzzOptions& options) {
  nlohmann::json j = fuzz_json(r);
  j["shard"] = {{"kind", "fuzz"},
                {"index", options.shard.index},
                {"count", options.shard.count},
                {"identity", {{"subject", options.subject}, {"methods", options.methods}, {"budget", options.budget},
                              {"seed", options.seed}, {"pixels", options.pixels}, {"hold_conservative", options.hold_conservative}}},
                {"first_failing_case", r.first_failing_case},
                {"per_case", r.per_case}};
  return j;
}

nlohmann::json merge_fuzz_shards(const std::vector<nlohmann::json>& documents, const std::vector<std::string>& names) {
  using nlohmann::json;
  const std::vector<const json*> by_index = shards_in_order(documents, names);
  // The failure the unsharded run meets first: the lowest first failing case of any shard.
  const json* winner = by_index[0];
  std::int64_t first = -1;
  for (const json* d : by_index) {
    const std::int64_t f = (*d)["shard"].at("first_failing_case").get<std::int64_t>();
    if (f >= 0 && (first < 0 || f < first)) first = f, winner = d;
  }
  json out = *winner;
  out.erase("shard");
  // The counts over the cases the unsharded run ran: every case up to that failure, or all.
  std::map<std::string, int> kinds, scenes;
  std::map<std::string, std::uint64_t> checked, skipped;
  std::uint64_t oracle_frames = 0, recheck_checked = 0, recheck_dropped = 0, cases = 0;
  json by_method = json::object();
  for (const json* d : by_index) {
    cases = std::max<std::uint64_t>(cases, (*d).at("cases").get<std::uint64_t>());
    for (const json& record : (*d)["shard"].at("per_case")) {
      if (first >= 0 && record.at("case").get<std::int64_t>() > first) continue;
      ++kinds[record.at("kind").get<std::string>()];
      ++scenes[record.at("scene").get<std::string>()];
      oracle_frames += record.at("oracle_frames").get<std::uint64_t>();
      recheck_checked += record.at("recheck")[0].get<std::uint64_t>();
      recheck_dropped += record.at("recheck")[1].get<std::uint64_t>();
      for (const auto& [method, m] : record.at("methods").items()) {
        skipped[method] += m[1].get<std::uint64_t>();
        if (!m[4].get<bool>()) continue;
        checked[method] += m[0].get<std::uint64_t>();
        json& b = by_method[method];
        if (b.is_null()) b = {{"checked", 0}, {"dropped", 0}};
        b["checked"] = b["checked"].get<std::uint64_t>() + m[2].get<std::uint64_t>();
        b["dropped"] = b["dropped"].get<std::uint64_t>() + m[3].get<std::uint64_t>();
      }
    }
  }
  out["cases"] = first >= 0 ? static_cast<std::uint64_t>(first) + 1 : cases;
  out["cases_by_path_kind"] = kinds;
  out["cases_by_scene_generator"] = scenes;
  out["oracle_frames"] = oracle_frames;
  out["checked_frames_by_method"] = checked;
  out["skipped_frames_by_method"] = skipped;
  out["witness_recheck"] = {{"checked", recheck_checked}, {"dropped", recheck_dropped}};
  if (!by_method.empty()) out["witness_recheck"]["by_method"] = by_method;
  return out;
}

}  // namespace cullcheck
