#include "reports/verification_json.hpp"

#include "core/errors.hpp"
#include "core/scene_io.hpp"

namespace cullcheck {

using nlohmann::json;

namespace {

json vec3(Vec3 p) { return json::array({p.x, p.y, p.z}); }

// Reads fields of one object, naming the object and field when one is missing or wrong.
class Reader {
 public:
  Reader(const json& j, std::string what) : j_(j), what_(std::move(what)) {
    if (!j_.is_object()) throw InputError(what_, "", "is not a JSON object");
  }
  template <class T>
  T get(const char* key) const {
    const auto it = j_.find(key);
    if (it == j_.end()) throw InputError(what_, key, "is missing");
    try {
      return it->template get<T>();
    } catch (const json::exception&) {
      throw InputError(what_, key, "has the wrong type: " + it->dump().substr(0, 80));
    }
  }
  const json& at(const char* key) const {
    const auto it = j_.find(key);
    if (it == j_.end()) throw InputError(what_, key, "is missing");
    return *it;
  }
  bool has(const char* key) const { return j_.contains(key); }
  Vec3 vec(const char* key) const {
    const auto a = get<std::vector<double>>(key);
    if (a.size() != 3) throw InputError(what_, key, "is not [x, y, z]");
    return {a[0], a[1], a[2]};
  }
  std::string what(const std::string& sub) const { return what_ + "." + sub; }

 private:
  const json& j_;
  std::string what_;
};

json violation_json(const Violation& x) {
  return {{"frame", x.frame}, {"building", x.building}, {"camera", json::parse(camera_to_json_text(x.camera))},
          {"model", x.model}, {"witness", x.witness},   {"replay", x.replay}};
}
Violation violation_from(const json& j, const std::string& what) {
  const Reader r(j, what);
  Violation x;
  x.frame = r.get<std::size_t>("frame");
  x.building = r.get<ObjectId>("building");
  x.camera = camera_from_json_text(r.at("camera").dump(), what + ".camera");
  x.model = r.get<std::string>("model");
  x.witness = r.get<std::string>("witness");
  x.replay = r.get<std::string>("replay");
  return x;
}
json violations_json(const std::vector<Violation>& list) {
  json a = json::array();
  for (const Violation& x : list) a.push_back(violation_json(x));
  return a;
}
std::vector<Violation> violations_from(const json& j, const std::string& what) {
  if (!j.is_array()) throw InputError(what, "", "is not an array");
  std::vector<Violation> out;
  for (std::size_t k = 0; k < j.size(); ++k) out.push_back(violation_from(j[k], what + "[" + std::to_string(k) + "]"));
  return out;
}

json tally_json(const ViolationTally& t) { return {{"count", t.count}, {"frames", t.frames}, {"kept", violations_json(t.kept)}}; }
ViolationTally tally_from(const json& j, const std::string& what) {
  const Reader r(j, what);
  return {r.get<std::uint64_t>("count"), r.get<std::size_t>("frames"), violations_from(r.at("kept"), what + ".kept")};
}

json recheck_json(const oracle::WitnessRecheckCounts& c) { return {{"checked", c.checked}, {"dropped", c.dropped}}; }
oracle::WitnessRecheckCounts recheck_from(const json& j, const std::string& what) {
  const Reader r(j, what);
  oracle::WitnessRecheckCounts c;
  c.checked = r.get<std::uint64_t>("checked");
  c.dropped = r.get<std::uint64_t>("dropped");
  return c;
}

json ray_json(const oracle::WitnessRay& w) {
  return {{"origin", vec3(w.origin)}, {"direction", vec3(w.direction)}, {"t_near", w.t_near},     {"t_far", w.t_far},
          {"t_hit", w.t_hit},         {"hit_point", vec3(w.hit_point)}, {"target", vec3(w.target)}, {"triangle", w.triangle},
          {"aimed_at", w.aimed_at},   {"source", static_cast<int>(w.source)}};
}
oracle::WitnessRay ray_from(const json& j, const std::string& what) {
  const Reader r(j, what);
  oracle::WitnessRay w;
  w.origin = r.vec("origin");
  w.direction = r.vec("direction");
  w.t_near = r.get<double>("t_near");
  w.t_far = r.get<double>("t_far");
  w.t_hit = r.get<double>("t_hit");
  w.hit_point = r.vec("hit_point");
  w.target = r.vec("target");
  w.triangle = r.get<std::uint32_t>("triangle");
  w.aimed_at = r.get<ObjectId>("aimed_at");
  const int source = r.get<int>("source");
  if (source < 0 || source > static_cast<int>(oracle::RaySource::grazing)) throw InputError(what, "source", "is not a ray source");
  w.source = static_cast<oracle::RaySource>(source);
  return w;
}

json snapshot_json(const FrameSnapshot& s) {
  json rays = json::array();
  for (const oracle::WitnessRay& w : s.witness_rays) rays.push_back(ray_json(w));
  return {{"frame", s.frame}, {"camera", json::parse(camera_to_json_text(s.camera))}, {"pvs", s.pvs}, {"seen", s.seen},
          {"missed", s.missed}, {"witness_rays", rays}, {"overestimate", s.overestimate}};
}
FrameSnapshot snapshot_from(const json& j, const std::string& what) {
  const Reader r(j, what);
  FrameSnapshot s;
  s.frame = r.get<std::size_t>("frame");
  s.camera = camera_from_json_text(r.at("camera").dump(), what + ".camera");
  s.pvs = r.get<std::vector<ObjectId>>("pvs");
  s.seen = r.get<std::vector<ObjectId>>("seen");
  s.missed = r.get<std::vector<ObjectId>>("missed");
  const json& rays = r.at("witness_rays");
  if (!rays.is_array()) throw InputError(what, "witness_rays", "is not an array");
  for (std::size_t k = 0; k < rays.size(); ++k) s.witness_rays.push_back(ray_from(rays[k], what + ".witness_rays"));
  s.overestimate = r.get<std::size_t>("overestimate");
  return s;
}

json statistics_json(const CullStatistics& s) {
  return {{"cells_tested", s.cells_tested},           {"buildings_tested", s.buildings_tested}, {"horizon_nodes", s.horizon_nodes},
          {"occluders_applied", s.occluders_applied}, {"items_skipped", s.items_skipped},       {"guard_fires", s.guard_fires},
          {"bound_tests", s.bound_tests},           {"exact_traversal_tests", s.exact_traversal_tests}};
}
CullStatistics statistics_from(const json& j, const std::string& what) {
  const Reader r(j, what);
  CullStatistics s;
  s.cells_tested = r.get<std::uint64_t>("cells_tested");
  s.buildings_tested = r.get<std::uint64_t>("buildings_tested");
  s.horizon_nodes = r.get<std::uint64_t>("horizon_nodes");
  s.occluders_applied = r.get<std::uint64_t>("occluders_applied");
  s.items_skipped = r.get<std::uint64_t>("items_skipped");
  s.guard_fires = r.get<std::uint64_t>("guard_fires");
  s.bound_tests = j.contains("bound_tests") ? r.get<std::uint64_t>("bound_tests") : 0;  // files from before it was counted
  s.exact_traversal_tests = j.contains("exact_traversal_tests") ? r.get<std::uint64_t>("exact_traversal_tests") : 0;  // likewise
  return s;
}

json run_json(const MethodRun& r) {
  json j = {{"method", r.method},
            {"claims_conservative", r.claims_conservative},
            {"outside", r.outside},
            {"pixel_error_budget", r.pixel_error_budget ? json(*r.pixel_error_budget) : json(nullptr)},
            {"cull_ms", r.cull_ms},
            {"answered_frames", r.answered_frames},
            {"pvs_size", r.pvs_size},
            {"checked_pvs_size", r.checked_pvs_size},
            {"witnessed_size", r.witnessed_size},
            {"checked_frames", r.checked_frames},
            {"snapshot", r.snapshot ? snapshot_json(*r.snapshot) : json(nullptr)},
            {"totals", statistics_json(r.totals)},
            {"witness_recheck", recheck_json(r.witness_recheck)},
            {"compared_with_reference", r.compared_with_reference},
            {"frames_differing_from_reference", r.frames_differing_from_reference},
            {"frames_skipped", r.frames_skipped},
            {"skip_reason", r.skip_reason},
            {"protocol_ms", r.protocol_ms},
            {"background_ms", r.background_ms},
            {"frames_equal_to", r.frames_equal_to},
            {"misdrawn_pixels", r.misdrawn_pixels},
            {"blob_per_frame", r.blob_per_frame},
            {"pixel_frames", r.pixel_frames},
            {"misdrawn_total", r.misdrawn_total},
            {"error_frames", r.error_frames},
            {"largest_blob", r.largest_blob},
            {"most_misdrawn", r.most_misdrawn},
            {"frames_over_budget", r.frames_over_budget},
            {"over_budget", violations_json(r.over_budget)},
            {"claims_every_camera", r.claims_every_camera},
            {"frames_claimed", r.frames_claimed},
            {"every_frame", tally_json(r.every_frame)},
            {"claimed_frames", tally_json(r.claimed_frames)}};
  return j;
}
MethodRun run_from(const json& j, const std::string& what) {
  const Reader r(j, what);
  MethodRun m;
  m.method = r.get<std::string>("method");
  m.claims_conservative = r.get<bool>("claims_conservative");
  m.outside = r.get<bool>("outside");
  if (!r.at("pixel_error_budget").is_null()) m.pixel_error_budget = r.get<std::uint64_t>("pixel_error_budget");
  m.cull_ms = r.get<std::vector<double>>("cull_ms");
  m.answered_frames = r.get<std::vector<std::size_t>>("answered_frames");
  m.pvs_size = r.get<std::vector<double>>("pvs_size");
  m.checked_pvs_size = r.get<std::vector<double>>("checked_pvs_size");
  m.witnessed_size = r.get<std::vector<double>>("witnessed_size");
  m.checked_frames = r.get<std::vector<std::size_t>>("checked_frames");
  if (!r.at("snapshot").is_null()) m.snapshot = snapshot_from(r.at("snapshot"), r.what("snapshot"));
  m.totals = statistics_from(r.at("totals"), r.what("totals"));
  m.witness_recheck = recheck_from(r.at("witness_recheck"), r.what("witness_recheck"));
  m.compared_with_reference = r.get<bool>("compared_with_reference");
  m.frames_differing_from_reference = r.get<std::size_t>("frames_differing_from_reference");
  m.frames_skipped = r.get<std::size_t>("frames_skipped");
  m.skip_reason = r.get<std::string>("skip_reason");
  m.protocol_ms = r.get<std::vector<double>>("protocol_ms");
  m.background_ms = j.value("background_ms", std::vector<double>{});  // absent before issue 17's prefetch figures
  m.frames_equal_to = r.get<std::vector<std::pair<std::string, std::size_t>>>("frames_equal_to");
  m.misdrawn_pixels = r.get<std::vector<double>>("misdrawn_pixels");
  m.blob_per_frame = r.get<std::vector<std::uint64_t>>("blob_per_frame");
  m.pixel_frames = r.get<std::vector<std::size_t>>("pixel_frames");
  m.misdrawn_total = r.get<std::uint64_t>("misdrawn_total");
  m.error_frames = r.get<std::size_t>("error_frames");
  m.largest_blob = r.get<std::uint64_t>("largest_blob");
  m.most_misdrawn = r.get<std::uint64_t>("most_misdrawn");
  m.frames_over_budget = r.get<std::size_t>("frames_over_budget");
  m.over_budget = violations_from(r.at("over_budget"), r.what("over_budget"));
  m.claims_every_camera = r.get<bool>("claims_every_camera");
  m.frames_claimed = r.get<std::size_t>("frames_claimed");
  m.every_frame = tally_from(r.at("every_frame"), r.what("every_frame"));
  m.claimed_frames = tally_from(r.at("claimed_frames"), r.what("claimed_frames"));
  settle_violations(m);
  return m;
}

json region_json(const RegionRun& r) {
  return {{"method", r.method},
          {"claims_conservative", r.claims_conservative},
          {"radius", r.radius},
          {"turn", r.turn},
          {"on_tiling", r.on_tiling},
          {"compute_ms", r.compute_ms},
          {"pvs_size", r.pvs_size},
          {"point_pvs_size", r.point_pvs_size},
          {"checked_pvs_size", r.checked_pvs_size},
          {"witnessed_size", r.witnessed_size},
          {"checked_frames", r.checked_frames},
          {"violation_count", r.violation_count},
          {"frames_with_violations", r.frames_with_violations},
          {"violations", violations_json(r.violations)},
          {"witness_recheck", recheck_json(r.witness_recheck)}};
}
RegionRun region_from(const json& j, const std::string& what) {
  const Reader r(j, what);
  RegionRun m;
  m.method = r.get<std::string>("method");
  m.claims_conservative = r.get<bool>("claims_conservative");
  m.radius = r.get<double>("radius");
  m.turn = r.get<double>("turn");
  m.on_tiling = r.get<bool>("on_tiling");
  m.compute_ms = r.get<std::vector<double>>("compute_ms");
  m.pvs_size = r.get<std::vector<double>>("pvs_size");
  m.point_pvs_size = r.get<std::vector<double>>("point_pvs_size");
  m.checked_pvs_size = r.get<std::vector<double>>("checked_pvs_size");
  m.witnessed_size = r.get<std::vector<double>>("witnessed_size");
  m.checked_frames = r.get<std::vector<std::size_t>>("checked_frames");
  m.violation_count = r.get<std::uint64_t>("violation_count");
  m.frames_with_violations = r.get<std::size_t>("frames_with_violations");
  m.violations = violations_from(r.at("violations"), r.what("violations"));
  m.witness_recheck = recheck_from(r.at("witness_recheck"), r.what("witness_recheck"));
  return m;
}

}  // namespace

json verification_to_json(const PathVerification& v) {
  json runs = json::array(), regions = json::array(), skipped = json::array();
  for (const MethodRun& r : v.runs) runs.push_back(run_json(r));
  for (const RegionRun& r : v.regions) regions.push_back(region_json(r));
  json density;
  oracle::to_json(density, v.oracle.density);
  const OracleSummary& o = v.oracle;
  json j = {{"runs", runs},
            {"regions", regions},
            {"checked_frames", v.checked_frames},
            {"checked_visible", v.checked_visible},
            {"oracle",
             {{"frames_checked", o.frames_checked},
              {"frames_exact_2d", o.frames_exact_2d},
              {"frames_ray_sampling", o.frames_ray_sampling},
              {"rays_cast", o.rays_cast},
              {"seconds", o.seconds},
              {"sampling_seconds", o.sampling_seconds},
              {"bare_embree_rays_per_second", o.bare_embree_rays_per_second},
              {"bare_embree_packet_rays_per_second", o.bare_embree_packet_rays_per_second},
              {"density", density},
              {"oracle_stride", o.oracle_stride},
              {"grazing_rays", o.grazing_rays},
              {"rays_skipped", o.rays_skipped},
              {"witness_recheck", recheck_json(o.witness_recheck)}}},
            {"pixels", {{"enabled", v.pixels.enabled}, {"frames", v.pixels.frames}, {"rays", v.pixels.rays}, {"seconds", v.pixels.seconds}}},
            {"skipped_methods", v.skipped_methods},
            {"frames_run", v.frames_run},
            {"aborted", nullptr}};
  if (v.aborted)
    j["aborted"] = {{"method", v.aborted->method}, {"frame", v.aborted->frame}, {"kind", v.aborted->kind}, {"message", v.aborted->message}};
  return j;
}

PathVerification verification_from_json(const json& j, const std::string& what) {
  const Reader r(j, what);
  PathVerification v;
  const json& runs = r.at("runs");
  const json& regions = r.at("regions");
  if (!runs.is_array() || !regions.is_array()) throw InputError(what, "runs", "runs and regions must be arrays");
  for (std::size_t k = 0; k < runs.size(); ++k) v.runs.push_back(run_from(runs[k], what + ".runs[" + std::to_string(k) + "]"));
  for (std::size_t k = 0; k < regions.size(); ++k)
    v.regions.push_back(region_from(regions[k], what + ".regions[" + std::to_string(k) + "]"));
  v.checked_frames = r.get<std::vector<std::size_t>>("checked_frames");
  v.checked_visible = r.get<std::vector<std::vector<ObjectId>>>("checked_visible");
  if (v.checked_frames.size() != v.checked_visible.size())
    throw InputError(what, "checked_visible", "has not one entry per checked frame");
  const Reader o(r.at("oracle"), r.what("oracle"));
  v.oracle.frames_checked = o.get<std::size_t>("frames_checked");
  v.oracle.frames_exact_2d = o.get<std::size_t>("frames_exact_2d");
  v.oracle.frames_ray_sampling = o.get<std::size_t>("frames_ray_sampling");
  v.oracle.rays_cast = o.get<std::uint64_t>("rays_cast");
  v.oracle.seconds = o.get<double>("seconds");
  v.oracle.sampling_seconds = o.get<double>("sampling_seconds");
  v.oracle.bare_embree_rays_per_second = o.get<double>("bare_embree_rays_per_second");
  v.oracle.bare_embree_packet_rays_per_second = r.at("oracle").value("bare_embree_packet_rays_per_second", 0.0);
  oracle::from_json(o.at("density"), v.oracle.density);
  v.oracle.oracle_stride = o.get<std::size_t>("oracle_stride");
  v.oracle.grazing_rays = o.get<std::uint64_t>("grazing_rays");
  v.oracle.rays_skipped = r.at("oracle").value("rays_skipped", std::uint64_t(0));  // shards written before the stop cast every ray
  v.oracle.witness_recheck = recheck_from(o.at("witness_recheck"), r.what("oracle.witness_recheck"));
  const Reader p(r.at("pixels"), r.what("pixels"));
  v.pixels.enabled = p.get<bool>("enabled");
  v.pixels.frames = p.get<std::size_t>("frames");
  v.pixels.rays = p.get<std::uint64_t>("rays");
  v.pixels.seconds = p.get<double>("seconds");
  v.skipped_methods = r.get<std::vector<std::pair<std::string, std::string>>>("skipped_methods");
  v.frames_run = r.get<std::size_t>("frames_run");
  if (!r.at("aborted").is_null()) {
    const Reader a(r.at("aborted"), r.what("aborted"));
    v.aborted = Abort{a.get<std::string>("method"), a.get<std::int64_t>("frame"), a.get<std::string>("kind"), a.get<std::string>("message")};
  }
  return v;
}

json claim_to_raw_json(const ClaimCheck& c) {
  json j = to_json(c);
  j["counterexample_scene"] = c.counterexample_scene;
  j["counterexample_replay"] = c.counterexample_replay;
  j["counterexample_detail"] = c.counterexample_detail;
  return j;
}

ClaimCheck claim_from_raw_json(const json& j, const std::string& what) {
  const Reader r(j, what);
  ClaimCheck c;
  c.id = r.get<std::string>("id");
  c.source = r.get<std::string>("source");
  c.statement = r.get<std::string>("statement");
  c.method = r.get<std::string>("method");
  c.holds = r.get<bool>("holds");
  c.frames_checked = r.get<std::uint64_t>("frames_checked");
  c.violations = r.get<std::uint64_t>("violations");
  c.search_seconds = r.get<double>("search_seconds");
  c.counterexample_scene = r.get<int>("counterexample_scene");
  c.counterexample_replay = r.get<std::string>("counterexample_replay");
  c.counterexample_detail = r.get<std::string>("counterexample_detail");
  return c;
}

}  // namespace cullcheck
