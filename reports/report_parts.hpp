// What `cullcheck report` found, before it is written as report.json, and the shards of one run
// (`--shard K/N`, core/shard.hpp) as such parts: a shard file is the report of its share (it
// reads like any report.json) with the raw parts under "shard", and `cullcheck merge` joins
// the raw parts of N shard files (shard_merge.hpp) and assembles them as one run would.
//
// The work of a run is split so: the oracle's checked frames and each claim search's scenes by
// number (shard n mod N), the knob sweep's checks with the frames they are held at, the view
// cells by number, and each other section (region_sweep, table_4_1, vbaoi, scaling, fuzz, soak,
// benchmarks) as one unit: the j-th section the run asks for is shard j mod N's. Every shard runs the methods
// along the whole path: an incremental method's answer depends on the frames before.
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/shard.hpp"
#include "engine/method.hpp"
#include "reports/claims.hpp"
#include "reports/gate_verdict.hpp"
#include "reports/knob_sweep.hpp"
#include "reports/verification.hpp"

namespace cullcheck {

// The sections a report may hold besides the path's, in report order (their claims follow the
// path's and the searches' in this order too).
const std::vector<std::string>& report_section_names();

struct ReportParts {
  nlohmann::json header;  // report_header (report.hpp): tool, machine, scene, path
  PathVerification verification;
  MethodOptions method_options;
  std::string map_method;
  std::optional<std::size_t> map_frame;
  std::vector<ClaimCheck> searched_claims;  // the claim searches, in order
  std::optional<std::vector<KnobRow>> knob_rows;
  std::optional<nlohmann::json> view_cell_rows;  // view_cells.hpp: this run's (shard's) cells
  nlohmann::json sections = nlohmann::json::object();  // by name: the sections this run (shard) ran
  std::map<std::string, std::vector<ClaimCheck>> section_claims;
  // What every shard of one run shares (the flags that change results): merge refuses shards
  // whose identities differ.
  nlohmann::json identity = nlohmann::json::object();
};

struct AssembledReport {
  nlohmann::json document;  // report.json
  std::vector<ClaimCheck> claims;  // the ledger, in document order
  GateVerdict verdict;
};

// report.json from the parts: the path's results, the claims ledger (the subjects', the
// searches', the sections'), the sections, and the gate (sections' violations counted).
AssembledReport assemble_report(const ReportParts& parts);
// Violations of the sections' conservative methods (table_4_1, view_cells, vbaoi), which the gate counts.
std::uint64_t section_gate_violations(const nlohmann::json& document);

// A shard's file: `report` (assemble_report(parts).document, the report of its share) with the
// raw parts under "shard".
nlohmann::json shard_document(nlohmann::json report, const ReportParts& parts, const Shard& shard);
// Reads N shard files (their texts' JSON, named for errors) into the parts of the whole run.
// Throws InputError naming the file and what is wrong: not a shard file, shards of other runs,
// a shard missing or given twice, results that disagree.
ReportParts merge_shard_documents(const std::vector<nlohmann::json>& documents, const std::vector<std::string>& names);

}  // namespace cullcheck
