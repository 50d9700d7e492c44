#include "reports/report_parts.hpp"

#include <algorithm>

#include "core/errors.hpp"
#include "reports/polar_table.hpp"
#include "reports/radar_table.hpp"
#include "reports/report.hpp"
#include "reports/shard_merge.hpp"
#include "reports/slice_wise_table.hpp"
#include "reports/speed_targets.hpp"
#include "reports/subject_claims.hpp"
#include "reports/vbaoi.hpp"
#include "reports/view_cells.hpp"
#include "reports/verification_json.hpp"

namespace cullcheck {

using nlohmann::json;

const std::vector<std::string>& report_section_names() {
  static const std::vector<std::string> names = {"region_sweep", "table_4_1", "online_culling", "radar_echo", "polar_diagram", "slice_wise", "vbaoi", "scaling", "fuzz", "soak", "benchmarks"};
  return names;
}

std::uint64_t section_gate_violations(const json& document) {
  std::uint64_t n = 0;
  if (document.contains("table_4_1"))
    for (const auto& r : document["table_4_1"]["rows"])
      if (r.value("claims_conservative", true)) n += r["violations"].get<std::uint64_t>();
  if (document.contains("view_cells"))
    for (const auto& r : document["view_cells"]["runs"])
      if (r["claims_conservative"].get<bool>()) n += r["violations"].get<std::uint64_t>();
  if (document.contains("vbaoi")) n += vbaoi_gate_violations(document["vbaoi"]);
  if (document.contains("radar_echo")) n += radar_table_violations(document["radar_echo"]);
  if (document.contains("polar_diagram")) n += polar_table_mismatches(document["polar_diagram"]);
  if (document.contains("slice_wise")) n += slice_table_violations(document["slice_wise"]);
  return n;
}

AssembledReport assemble_report(const ReportParts& parts) {
  AssembledReport out;
  ReportInputs in;
  in.verification = &parts.verification;
  in.method_options = parts.method_options;
  in.map_method = parts.map_method;
  in.map_frame = parts.map_frame;
  in.claims = subject_claims(parts.verification);
  in.claims.insert(in.claims.end(), parts.searched_claims.begin(), parts.searched_claims.end());
  out.document = report_results(in, parts.header);
  out.claims = in.claims;
  if (parts.knob_rows) out.document["knob_sweep"] = knob_sweep_json(*parts.knob_rows);
  if (parts.view_cell_rows) out.document["view_cells"] = view_cell_section(*parts.view_cell_rows);
  for (const std::string& name : report_section_names()) {
    if (parts.sections.contains(name)) out.document[name] = parts.sections[name];
    if (const auto found = parts.section_claims.find(name); found != parts.section_claims.end())
      for (const ClaimCheck& c : found->second) {
        out.document["claims"].push_back(to_json(c));
        out.claims.push_back(c);
      }
  }
  // The gate in the document says what the exit code says: sections' violations count too.
  out.verdict = gate_verdict(parts.verification, parts.header["scene"]["replay_flags"].get<std::string>(), {},
                             section_gate_violations(out.document));
  out.document["gate"] = out.verdict.to_json();
  out.document["speed_targets"] = speed_targets(out.document);
  return out;
}

namespace {

MethodOptions method_options_from(const json& j) {
  MethodOptions o;
  o.horizon_bins = j.at("horizon_bins").get<std::uint32_t>();
  o.quadtree_leaf_size = j.at("quadtree_leaf_size").get<std::uint32_t>();
  o.delta_radius = j.at("delta_radius").get<double>();
  o.delta_height = j.at("delta_height").get<double>();
  o.delta_turn = j.at("delta_turn").get<double>();
  o.delta_prefetch = j.value("delta_prefetch", true);  // absent before issue 17
  return o;
}

}  // namespace

json shard_document(json document, const ReportParts& parts, const Shard& shard) {
  json claims = json::array(), sections = json::array(), section_claims = json::object();
  for (const ClaimCheck& c : parts.searched_claims) claims.push_back(claim_to_raw_json(c));
  for (const std::string& name : report_section_names())
    if (parts.sections.contains(name)) sections.push_back(name);
  for (const auto& [name, list] : parts.section_claims) {
    section_claims[name] = json::array();
    for (const ClaimCheck& c : list) section_claims[name].push_back(claim_to_raw_json(c));
  }
  json knob_rows = nullptr;
  if (parts.knob_rows) {
    knob_rows = json::array();
    for (const KnobRow& r : *parts.knob_rows) knob_rows.push_back(knob_row_to_raw_json(r));
  }
  document["shard"] = {{"kind", "report"},
                       {"index", shard.index},
                       {"count", shard.count},
                       {"identity", parts.identity},
                       {"verification", verification_to_json(parts.verification)},
                       {"method_options", method_options_json(parts.method_options)},
                       {"map_method", parts.map_method},
                       {"map_frame", parts.map_frame ? json(*parts.map_frame) : json(nullptr)},
                       {"searched_claims", claims},
                       {"knob_rows", knob_rows},
                       {"view_cell_rows", parts.view_cell_rows ? *parts.view_cell_rows : json(nullptr)},
                       {"sections_run", sections},
                       {"section_claims", section_claims}};
  return document;
}

ReportParts merge_shard_documents(const std::vector<json>& documents, const std::vector<std::string>& names) {
  std::vector<std::string> name_of;
  const std::vector<const json*> by_index = shards_in_order(documents, names, &name_of);
  const json& first = *by_index[0];
  for (std::size_t k = 1; k < by_index.size(); ++k)
    for (const char* key : {"scene", "path"})
      if (by_index[k]->value(key, json()) != first.value(key, json()))
        throw InputError(name_of[k], key, "differs from shard 0's (" + name_of[0] + ", key '" +
                                              first_difference(first.value(key, json()), by_index[k]->value(key, json())) +
                                              "'): not a shard of the same run");
  ReportParts parts;
  try {
    for (const char* key : {"schema_version", "tool", "machine", "scene", "path"})
      if (first.contains(key)) parts.header[key] = first[key];
    const json& raw = first["shard"];
    parts.identity = raw.at("identity");
    parts.method_options = method_options_from(raw.at("method_options"));
    parts.map_method = raw.at("map_method").get<std::string>();
    if (!raw.at("map_frame").is_null()) parts.map_frame = raw.at("map_frame").get<std::size_t>();
    std::vector<PathVerification> verifications;
    std::vector<std::vector<ClaimCheck>> claims;
    std::vector<std::vector<KnobRow>> knobs;
    std::vector<json> cells;
    for (std::size_t k = 0; k < by_index.size(); ++k) {
      const json& s = (*by_index[k])["shard"];
      verifications.push_back(verification_from_json(s.at("verification"), name_of[k] + ": shard.verification"));
      claims.emplace_back();
      for (const json& c : s.at("searched_claims")) claims.back().push_back(claim_from_raw_json(c, name_of[k] + ": shard.searched_claims"));
      if (!s.at("knob_rows").is_null()) {
        knobs.emplace_back();
        for (const json& r : s.at("knob_rows")) knobs.back().push_back(knob_row_from_raw_json(r, name_of[k] + ": shard.knob_rows"));
      }
      if (!s.at("view_cell_rows").is_null()) cells.push_back(s["view_cell_rows"]);
      for (const json& name : s.at("sections_run")) {
        const std::string section = name.get<std::string>();
        if (parts.sections.contains(section))
          throw InputError(name_of[k], "shard.sections_run", "section " + section + " was run by another shard too");
        parts.sections[section] = by_index[k]->at(section);
        if (s.at("section_claims").contains(section)) {
          std::vector<ClaimCheck>& list = parts.section_claims[section];
          for (const json& c : s["section_claims"][section])
            list.push_back(claim_from_raw_json(c, name_of[k] + ": shard.section_claims." + section));
        }
      }
    }
    const std::size_t max_replays = parts.identity.value("max_replays", std::size_t{5});
    parts.verification = merge_verifications(verifications, max_replays);
    parts.searched_claims = merge_claims(claims);
    if (!cells.empty()) {
      if (cells.size() != by_index.size()) throw InputError("merge", "view_cell_rows", "some shards computed view cells and some did not");
      parts.view_cell_rows = merge_view_cell_rows(cells);
    }
    if (!knobs.empty()) {
      if (knobs.size() != by_index.size()) throw InputError("merge", "knob_rows", "some shards swept knobs and some did not");
      parts.knob_rows = merge_knob_rows(knobs);
    }
  } catch (const json::exception& e) {
    throw InputError("merge", "shard", std::string("a shard file is malformed: ") + e.what());
  }
  return parts;
}

}  // namespace cullcheck
