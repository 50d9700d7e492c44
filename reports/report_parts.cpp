#include "reports/report_parts.hpp"

#include <algorithm>

#include "core/errors.hpp"
#include "reports/report.hpp"
#include "reports/shard_merge.hpp"
#include "reports/subject_claims.hpp"
#include "reports/vbaoi.hpp"
#include "reports/view_cells.hpp"
#include "reports/verification_json.hpp"

namespace cullcheck {

using nlohmann::json;

const std::vector<std::string>& report_section_names() {
  static const std::vector<std::string> names = {"region_sweep", "table_4_1", "vbaoi", "scaling", "fuzz", "soak", "benchmarks"};
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
  return out;
}

namespace {

json method_options_json(const MethodOptions& o) {
  return {{"horizon_bins", o.horizon_bins},
          {"quadtree_leaf_size", o.quadtree_leaf_size},
          {"delta_radius", o.delta_radius},
          {"delta_height", o.delta_height},
          {"delta_turn", o.delta_turn}};
}
MethodOptions method_options_from(const json& j) {
  MethodOptions o;
  o.horizon_bins = j.at("horizon_bins").get<std::uint32_t>();
  o.quadtree_leaf_size = j.at("quadtree_leaf_size").get<std::uint32_t>();
  o.delta_radius = j.at("delta_radius").get<double>();
  o.delta_height = j.at("delta_height").get<double>();
  o.delta_turn = j.at("delta_turn").get<double>();
  return o;
}

// The first key whose value differs between two objects (for an error that says what differs).
std::string first_difference(const json& a, const json& b) {
  if (!a.is_object() || !b.is_object()) return "";
  for (const auto& [key, value] : a.items())
    if (!b.contains(key) || b[key] != value) return key;
  for (const auto& [key, value] : b.items())
    if (!a.contains(key)) return key;
  return "";
}

}  // namespace

json shard_document(const ReportParts& parts, const Shard& shard) {
  json document = assemble_report(parts).document;
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
  if (documents.empty()) throw InputError("merge", "shards", "no shard files given");
  // Every file a shard file, of the same count, each index once.
  std::vector<const json*> by_index(documents.size(), nullptr);
  std::vector<std::string> name_of(documents.size());
  for (std::size_t k = 0; k < documents.size(); ++k) {
    const json& d = documents[k];
    if (!d.is_object() || !d.contains("shard") || !d["shard"].is_object())
      throw InputError(names[k], "shard", "is missing: not a shard file (write one with `cullcheck report --shard K/N`)");
    const json& s = d["shard"];
    if (!s.contains("index") || !s.contains("count") || !s["index"].is_number_unsigned() || !s["count"].is_number_unsigned())
      throw InputError(names[k], "shard", "has no index and count");
    const std::size_t index = s["index"], count = s["count"];
    if (count != documents.size())
      throw InputError(names[k], "shard.count", "is " + std::to_string(count) + ", but " + std::to_string(documents.size()) +
                                                    " shard files were given: every shard of the run is needed, once");
    if (index >= count) throw InputError(names[k], "shard.index", std::to_string(index) + " is not below the count");
    if (by_index[index])
      throw InputError(names[k], "shard.index", "shard " + std::to_string(index) + " is given twice (also " + name_of[index] + ")");
    by_index[index] = &d;
    name_of[index] = names[k];
  }
  const json& first = *by_index[0];
  for (std::size_t k = 1; k < by_index.size(); ++k) {
    const json& d = *by_index[k];
    for (const char* key : {"scene", "path"})
      if (d.value(key, json()) != first.value(key, json()))
        throw InputError(name_of[k], key, "differs from shard 0's (" + name_of[0] + ", key '" +
                                              first_difference(first.value(key, json()), d.value(key, json())) +
                                              "'): not a shard of the same run");
    if (d["shard"].value("identity", json()) != first["shard"].value("identity", json()))
      throw InputError(name_of[k], "shard.identity",
                       "differs from shard 0's (" + name_of[0] + ") in '" +
                           first_difference(first["shard"]["identity"], d["shard"]["identity"]) +
                           "': the shards were run with other flags");
  }
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
