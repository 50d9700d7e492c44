#include "reports/vbaoi.hpp"

#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "core/errors.hpp"
#include "core/scene_io.hpp"
#include "oracle/ray_oracle.hpp"
#include "reports/statistics.hpp"

namespace cullcheck {
namespace {

std::vector<double> as_doubles(const std::vector<std::uint64_t>& v) { return {v.begin(), v.end()}; }

nlohmann::json spread(const std::vector<double>& v) {
  if (v.empty()) return {{"mean", 0.0}, {"median", 0.0}, {"p95", 0.0}, {"max", 0.0}};
  return {{"mean", mean(v)}, {"median", median(v)}, {"p95", percentile(v, 95.0)}, {"max", percentile(v, 100.0)}};
}

std::string hex(std::uint64_t x) {
  char buffer[20];
  std::snprintf(buffer, sizeof buffer, "%016llx", static_cast<unsigned long long>(x));
  return buffer;
}

nlohmann::json graph_json(const Scene& scene, const NavigationGraph& graph) {
  std::vector<double> pvs_o, pvs_n, neighbours, pvs_o_bytes;
  std::map<ObjectId, const Building*> by_id;
  for (const Building& b : scene.buildings) by_id[b.id] = &b;
  for (const NavigationNode& n : graph.nodes) {
    pvs_o.push_back(static_cast<double>(n.pvs_o.size()));
    pvs_n.push_back(static_cast<double>(n.pvs_n.size()));
    neighbours.push_back(static_cast<double>(n.neighbours.size()));
    std::uint64_t bytes = 0;
    for (ObjectId id : n.pvs_o) bytes += vbaoi::building_bytes(*by_id.at(id));
    pvs_o_bytes.push_back(static_cast<double>(bytes));
  }
  const std::vector<std::string> problems = graph_invariant_violations(graph);
  nlohmann::json first_problems = nlohmann::json::array();
  for (std::size_t i = 0; i < problems.size() && i < 10; ++i) first_problems.push_back(problems[i]);
  return {{"nodes", graph.nodes.size()},
          {"buildings", scene.buildings.size()},
          {"method", graph.options.method},
          {"claims_conservative", graph.method_claims_conservative},
          {"epsilon", graph.options.epsilon},
          {"eye_height", graph.options.eye_height},
          {"sampling", std::string(cell_sampling_name(graph.options.sampling))},
          {"threads", graph.options.threads},
          {"build_seconds", graph.stats.build_seconds},
          {"node_ms", spread(graph.stats.node_ms)},
          {"samples", graph.stats.samples},
          {"pvs_o", spread(pvs_o)},
          {"pvs_o_fraction_of_city", scene.buildings.empty() ? 0.0 : mean(pvs_o) / static_cast<double>(scene.buildings.size())},
          {"pvs_o_bytes", spread(pvs_o_bytes)},
          {"whole_city_bytes", vbaoi::whole_city_bytes(scene)},
          {"pvs_n", spread(pvs_n)},
          {"pvs_n_fraction_of_nodes", graph.nodes.empty() ? 0.0 : mean(pvs_n) / static_cast<double>(graph.nodes.size())},
          {"neighbours", spread(neighbours)},
          {"pvs_n_symmetry", std::string(pvs_n_symmetry_name(graph.options.symmetry))},
          {"pvs_n_one_sided", graph.stats.pvs_n_one_sided},
          {"pvs_n_added_neighbours", graph.stats.pvs_n_added_neighbours},
          {"digest", hex(graph_digest(graph))},
          {"invariant_violations", problems.size()},
          {"invariant_problems", first_problems}};
}

// The command that shows one grouping violation: the line of sight between the two clients' eyes
// (oracle) and whether the graph's method lists the second client's node in the first's raw PVSn.
std::string grouping_replay(const SceneSource& source, const VbaoiOptions& o, const vbaoi::GroupingExample& e) {
  Camera eye;
  eye.hfov = kTwoPi;
  eye.position = {e.position_a.x, e.position_a.y, o.graph.eye_height};
  return "cullcheck cell " + source.replay_flags() + " --method " + o.graph.method + " --cell " + std::to_string(e.node_a) +
         " --epsilon " + round_trip_text(o.graph.epsilon) + " --sampling " +
         std::string(cell_sampling_name(o.graph.sampling)) + " --eye-height " + round_trip_text(o.graph.eye_height) +
         " --cell-size " + round_trip_text(o.regions.cell_size) + " --cell-margin " + round_trip_text(o.regions.margin) +
         " --nodes --from " + camera_arg(eye) + " --to " + round_trip_text(e.position_b.x) + "," +
         round_trip_text(e.position_b.y);
}

nlohmann::json run_json(const vbaoi::SimulationResult& r, const SceneSource& source, const VbaoiOptions& options) {
  nlohmann::json policies = nlohmann::json::array();
  const double vbaoi_messages = r.policies.empty() ? 0.0 : static_cast<double>(r.policies[0].messages);
  for (const vbaoi::PolicyTraffic& p : r.policies) {
    nlohmann::json examples = nlohmann::json::array();
    for (const vbaoi::GroupingExample& e : p.first_violations)
      examples.push_back({{"tick", e.tick},
                          {"clients", {e.a, e.b}},
                          {"positions", {{e.position_a.x, e.position_a.y}, {e.position_b.x, e.position_b.y}}},
                          {"nodes", {e.node_a, e.node_b}},
                          {"replay", grouping_replay(source, options, e)}});
    policies.push_back({{"policy", p.policy},
                        {"radius", p.radius},
                        {"messages", p.messages},
                        {"bytes", p.bytes},
                        {"update_deliveries", p.update_deliveries},
                        {"checked_update_deliveries", p.checked_update_deliveries},
                        {"deliveries_vs_limit",
                         p.visible_updates > 0
                             ? static_cast<double>(p.checked_update_deliveries) / static_cast<double>(p.visible_updates)
                             : 0.0},
                        {"messages_per_tick", spread(as_doubles(p.messages_per_tick))},
                        {"bytes_per_tick", spread(as_doubles(p.bytes_per_tick))},
                        {"messages_vs_vbaoi", vbaoi_messages > 0 ? static_cast<double>(p.messages) / vbaoi_messages : 0.0},
                        {"visible_updates", p.visible_updates},
                        {"missed_updates", p.missed_updates},
                        {"lost_updates", p.lost_updates},
                        {"grouping_violations", p.grouping_violations},
                        {"first_violations", examples}});
  }
  nlohmann::json by_kind = nlohmann::json::object();
  for (std::size_t k = 0; k < vbaoi::kMessageKinds; ++k)
    by_kind[std::string(vbaoi::message_kind_name(static_cast<vbaoi::MessageKind>(k)))] = {
        {"messages", r.messages_by_kind[k]}, {"bytes", r.bytes_by_kind[k]}};
  const vbaoi::SimulationOptions& o = r.options;
  return {{"clients", o.clients},
          {"seed", o.seed},
          {"duration", o.duration},
          {"tick", o.tick},
          {"latency", o.latency},
          {"jitter", o.jitter},
          {"loss", o.loss},
          {"retry_timeout", o.retry_timeout},
          {"join_window", o.join_window},
          {"speed_min", o.speed_min},
          {"speed_max", o.speed_max},
          {"check_stride", o.check_stride},
          {"ticks", r.ticks},
          {"checked_ticks", r.checked_ticks},
          {"active_client_ticks", r.active_client_ticks},
          {"pairs_checked", r.pairs_checked},
          {"visible_pairs", r.visible_pairs},
          {"policies", policies},
          {"vbaoi",
           {{"clients_active", r.clients_active},
            {"handovers", r.handovers},
            {"stall_ticks", r.stall_ticks},
            {"resent", r.resent},
            {"render_violations", r.render_violations},
            {"outside_node", r.outside_node},
            {"join_seconds", spread(r.join_seconds)},
            {"join_bytes", spread(as_doubles(r.join_bytes))},
            {"whole_city_bytes", r.whole_city_bytes},
            {"join_bytes_fraction_of_city",
             r.whole_city_bytes == 0 || r.join_bytes.empty()
                 ? 0.0
                 : median(as_doubles(r.join_bytes)) / static_cast<double>(r.whole_city_bytes)},
            {"listened_channels", spread(r.listened_channels)},
            {"messages_by_kind", by_kind}}},
          {"digest", hex(r.digest)},
          {"wall_seconds", r.wall_seconds},
          {"line_of_sight_seconds", r.line_of_sight_seconds}};
}

}  // namespace

std::string vbaoi_replay_command(const SceneSource& source, const VbaoiOptions& o, std::uint32_t clients) {
  const vbaoi::SimulationOptions& s = o.simulation;
  std::ostringstream out;
  out << "cullcheck vbaoi " << source.replay_flags() << " --graph-method " << o.graph.method << " --epsilon "
      << round_trip_text(o.graph.epsilon) << " --clients " << clients << " --sim-seed " << s.seed << " --duration "
      << round_trip_text(s.duration) << " --tick " << round_trip_text(s.tick) << " --latency "
      << round_trip_text(s.latency) << " --jitter " << round_trip_text(s.jitter) << " --loss "
      << round_trip_text(s.loss) << " --retry-timeout " << round_trip_text(s.retry_timeout) << " --join-window "
      << round_trip_text(s.join_window) << " --speed-min " << round_trip_text(s.speed_min) << " --speed-max "
      << round_trip_text(s.speed_max) << " --check-stride " << s.check_stride << " --circular-radii ";
  for (std::size_t i = 0; i < s.circular_radii.size(); ++i) out << (i ? "," : "") << round_trip_text(s.circular_radii[i]);
  if (o.graph.sampling != CellSampling::boundary) out << " --graph-sampling " << cell_sampling_name(o.graph.sampling);
  out << " --pvs-n-symmetry " << pvs_n_symmetry_name(o.graph.symmetry) << " --eye-height " << round_trip_text(o.graph.eye_height) << " --cell-size "
      << round_trip_text(o.regions.cell_size) << " --cell-margin " << round_trip_text(o.regions.margin);
  return out.str();
}

nlohmann::json vbaoi_report(const Scene& scene, const SceneSource& source, const VbaoiOptions& options) {
  vbaoi::validate(options.simulation);
  const std::vector<NavigableRegion> regions = generators::navigable_regions(scene, options.regions);
  const NavigationGraph graph = build_navigation_graph(scene, regions, options.graph);
  nlohmann::json out;
  out["scene"] = {{"generator", scene.provenance.generator},
                  {"seed", scene.provenance.seed},
                  {"parameters", nlohmann::json::parse(scene.provenance.parameters_json)},
                  {"building_count", scene.buildings.size()},
                  {"replay_flags", source.replay_flags()}};
  out["graph"] = graph_json(scene, graph);
  const oracle::RayOracle oracle(scene);
  const vbaoi::LineOfSight los = [&](const std::vector<Vec3>& eyes) {
    return oracle.mutually_visible(eyes, options.oracle_threads);
  };
  out["runs"] = nlohmann::json::array();
  for (std::uint32_t clients : options.client_counts) {
    vbaoi::SimulationOptions s = options.simulation;
    s.clients = clients;
    nlohmann::json run = run_json(vbaoi::simulate(scene, graph, s, los), source, options);
    run["replay"] = vbaoi_replay_command(source, options, clients);
    out["runs"].push_back(std::move(run));
  }
  return out;
}

namespace {

// A run's policy by name (the order of SimulationResult::policies may grow); throws when absent.
const nlohmann::json& policy_of(const nlohmann::json& run, const std::string& policy) {
  for (const auto& p : run["policies"])
    if (p["policy"] == policy) return p;
  throw std::invalid_argument("vbaoi report: a run has no policy \"" + policy + "\"");
}

}  // namespace

std::vector<ClaimCheck> vbaoi_claims(const nlohmann::json& report) {
  const auto& g = report["graph"];
  auto make = [&](std::string id, std::string statement, const std::string& policy,
                  std::string source = "Koldaş thesis ch. 5.1 (Fig. 5.2-5.3)") {
    ClaimCheck c;
    c.id = std::move(id);
    c.source = std::move(source);
    c.statement = std::move(statement);
    c.method = policy + " (graph: " + g["method"].get<std::string>() + ", " + g["sampling"].get<std::string>() +
               " samples, eps " + round_trip_text(g["epsilon"].get<double>()) + " m)";
    for (const auto& run : report["runs"]) {
      const auto& p = policy_of(run, policy);
      c.frames_checked += run["checked_ticks"].get<std::uint64_t>();
      c.violations += p["grouping_violations"].get<std::uint64_t>() + p["missed_updates"].get<std::uint64_t>();
      c.search_seconds += run["wall_seconds"].get<double>();
      if (c.holds && !p["first_violations"].empty()) {
        const auto& e = p["first_violations"][0];
        c.holds = false;
        c.counterexample_replay = e["replay"].get<std::string>();
        c.counterexample_detail = "with " + std::to_string(run["clients"].get<std::uint32_t>()) + " clients (" +
                                  run["replay"].get<std::string>() + "), at tick " + std::to_string(e["tick"].get<std::uint64_t>()) +
                                  " clients " + e["clients"][0].dump() + " and " + e["clients"][1].dump() + " in nodes " +
                                  e["nodes"][0].dump() + " and " + e["nodes"][1].dump() + " see each other (" +
                                  std::to_string(p["grouping_violations"].get<std::uint64_t>()) + " such pairs, " +
                                  std::to_string(p["missed_updates"].get<std::uint64_t>()) + " updates missed in that run)";
      }
    }
    c.holds = c.holds && c.violations == 0;
    return c;
  };
  return {make("thesis-5.1-vbaoi-channel-grouping",
               "Clients that publish on their node's channel and listen to the channels of its PVSn are mutually "
               "subscribed whenever they see each other, and receive each other's every update",
               "vbaoi"),
          make("thesis-5.1-listen-to-sns",
               "Listening to one's own node's channel and those of its SNs (ch. 5.1's wording) is enough to receive "
               "every client one can see",
               "neighbours"),
          make("vbaoi-server-sight-filter",
               "A server that forwards a channel's update only to listeners its sight filter cannot prove blind to the "
               "sender (engine/vbaoi/sight_filter.hpp) still delivers every update a listener can see",
               "vbaoi_filtered", "cullcheck (issue 17)")};
}

std::size_t vbaoi_gate_violations(const nlohmann::json& report) {
  if (!report["graph"]["claims_conservative"].get<bool>()) return 0;
  std::size_t n = report["graph"]["invariant_violations"].get<std::size_t>();
  for (const auto& run : report["runs"]) {
    for (const char* policy : {"vbaoi", "vbaoi_filtered"}) {
      const auto& v = policy_of(run, policy);
      n += v["grouping_violations"].get<std::size_t>() + v["missed_updates"].get<std::size_t>();
    }
    n += run["vbaoi"]["render_violations"].get<std::size_t>() + run["vbaoi"]["outside_node"].get<std::size_t>();
  }
  return n;
}

std::string vbaoi_table(const nlohmann::json& r) {
  std::ostringstream out;
  const auto& g = r["graph"];
  char line[512];
  std::snprintf(line, sizeof line,
                "vbaoi graph: %zu nodes, %zu buildings, %s eps %.3g m, built in %.1f s (%u threads, median %.1f ms/node); "
                "invariant violations %zu; digest %s\n",
                g["nodes"].get<std::size_t>(), g["buildings"].get<std::size_t>(), g["method"].get<std::string>().c_str(),
                g["epsilon"].get<double>(), g["build_seconds"].get<double>(), g["threads"].get<unsigned>(),
                g["node_ms"]["median"].get<double>(), g["invariant_violations"].get<std::size_t>(),
                g.value("digest", std::string("-")).c_str());
  out << line;
  std::snprintf(line, sizeof line,
                "  PVSo per node: mean %.1f, median %.0f, max %.0f buildings (%.2f%% of the city); %.0f KB median against "
                "%.0f KB for the whole city\n",
                g["pvs_o"]["mean"].get<double>(), g["pvs_o"]["median"].get<double>(), g["pvs_o"]["max"].get<double>(),
                100.0 * g["pvs_o_fraction_of_city"].get<double>(), g["pvs_o_bytes"]["median"].get<double>() / 1024.0,
                g["whole_city_bytes"].get<double>() / 1024.0);
  out << line;
  std::snprintf(line, sizeof line,
                "  PVSn per node: mean %.1f, median %.0f, max %.0f nodes (%.2f%% of the nodes); one-sided entries %llu "
                "(symmetry by %s), neighbours added %llu\n",
                g["pvs_n"]["mean"].get<double>(), g["pvs_n"]["median"].get<double>(), g["pvs_n"]["max"].get<double>(),
                100.0 * g["pvs_n_fraction_of_nodes"].get<double>(),
                static_cast<unsigned long long>(g["pvs_n_one_sided"].get<std::uint64_t>()),
                g["pvs_n_symmetry"].get<std::string>().c_str(),
                static_cast<unsigned long long>(g["pvs_n_added_neighbours"].get<std::uint64_t>()));
  out << line;
  out << "clients  policy          radius   msgs/tick  KB/tick  vs_vbaoi  visible_upd  vs_limit   missed    lost  grouping_viol\n";
  for (const auto& run : r["runs"]) {
    for (const auto& p : run["policies"]) {
      std::snprintf(line, sizeof line, "%7u  %-14s %7.0f %11.1f %8.1f %9.1f %12llu %9.2f %8llu %7llu %14llu\n",
                    run["clients"].get<unsigned>(), p["policy"].get<std::string>().c_str(), p["radius"].get<double>(),
                    p["messages_per_tick"]["mean"].get<double>(), p["bytes_per_tick"]["mean"].get<double>() / 1024.0,
                    p["messages_vs_vbaoi"].get<double>(),
                    static_cast<unsigned long long>(p["visible_updates"].get<std::uint64_t>()),
                    p.value("deliveries_vs_limit", 0.0),
                    static_cast<unsigned long long>(p["missed_updates"].get<std::uint64_t>()),
                    static_cast<unsigned long long>(p["lost_updates"].get<std::uint64_t>()),
                    static_cast<unsigned long long>(p["grouping_violations"].get<std::uint64_t>()));
      out << line;
    }
    const auto& v = run["vbaoi"];
    std::snprintf(line, sizeof line,
                  "         vbaoi: %u active, %llu handovers, %llu stall ticks, %llu resent, render without data %llu, "
                  "outside node %llu; join %.2f s median, %.0f KB median; %.1f channels listened (mean); %llu visible "
                  "pairs over %llu checked ticks; digest %s; %.1f s (line of sight %.1f s)\n",
                  v["clients_active"].get<unsigned>(), static_cast<unsigned long long>(v["handovers"].get<std::uint64_t>()),
                  static_cast<unsigned long long>(v["stall_ticks"].get<std::uint64_t>()),
                  static_cast<unsigned long long>(v["resent"].get<std::uint64_t>()),
                  static_cast<unsigned long long>(v["render_violations"].get<std::uint64_t>()),
                  static_cast<unsigned long long>(v["outside_node"].get<std::uint64_t>()),
                  v["join_seconds"]["median"].get<double>(), v["join_bytes"]["median"].get<double>() / 1024.0,
                  v["listened_channels"]["mean"].get<double>(),
                  static_cast<unsigned long long>(run["visible_pairs"].get<std::uint64_t>()),
                  static_cast<unsigned long long>(run["checked_ticks"].get<std::uint64_t>()),
                  run["digest"].get<std::string>().c_str(), run["wall_seconds"].get<double>(),
                  run["line_of_sight_seconds"].get<double>());
    out << line;
  }
  return out.str();
}

}  // namespace cullcheck
