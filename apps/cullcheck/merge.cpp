// cullcheck merge: the shard files of one run (`report`, `verify`, `fuzz` or `cell` with
// --shard K/N) joined into the report of the whole run, the one an unsharded run writes (timings
// aside).
#include <iostream>
#include <memory>
#include <set>

#include "apps/cullcheck/flags.hpp"
#include "apps/cullcheck/page_writer.hpp"
#include "apps/cullcheck/subcommands.hpp"
#include "core/errors.hpp"
#include "core/scene_io.hpp"
#include "reports/cell_shards.hpp"
#include "reports/fuzzing.hpp"
#include "reports/junit.hpp"
#include "reports/report.hpp"
#include "reports/report_parts.hpp"

namespace cullcheck::cli {

Runner add_merge(CLI::App& app) {
  struct Flags {
    std::vector<std::string> inputs;
    std::string output = "report.json", html, junit;
  };
  auto f = std::make_shared<Flags>();
  CLI::App* sub = app.add_subcommand(
      "merge", "Join the N shard files of one run (report, verify, fuzz or cell, written with --shard K/N) into the report of the "
              "whole run");
  sub->add_option("shards", f->inputs, "Every shard file of the run, in any order")->required();
  sub->add_option("--output,-o", f->output, "Report file to write")->capture_default_str();
  sub->add_option("--html", f->html, "Also write the report page (its map's scene is rebuilt from the report's scene flags)");
  sub->add_option("--junit", f->junit, "Also write the gate's checks as JUnit XML");
  return [f] {
    std::vector<nlohmann::json> documents;
    for (const std::string& input : f->inputs) documents.push_back(parse_json_flag(read_text_file(input), input));
    // The kind of each shard: "fuzz", "cell", or "" for report and verify shards.
    std::set<std::string> kinds;
    for (const nlohmann::json& d : documents)
      kinds.insert(d.is_object() && d.contains("shard") && d["shard"].is_object() ? d["shard"].value("kind", "") : "");
    if (kinds.size() > 1)
      throw InputError("merge", "shards", "shards of different commands (fuzz, cell, report or verify) cannot be merged together");
    // Shards of `cullcheck cell`: the cell's result.
    if (kinds.contains("cell")) {
      const nlohmann::json merged = merge_cell_shards(documents, f->inputs);
      write_text_file_atomically(f->output, merged.dump(2) + "\n");
      std::cout << "merged " << documents.size() << " cell shards: " << merged["samples"] << " samples, PVS of "
                << merged["pvs_size"] << " buildings\nwrote " << f->output << "\n";
      return 0;
    }
    // Shards of `cullcheck fuzz`: the summary of the unsharded run.
    if (kinds.contains("fuzz")) {
      const nlohmann::json merged = merge_fuzz_shards(documents, f->inputs);
      write_text_file_atomically(f->output, merged.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
      const bool failed = merged.contains("failure");
      std::cout << "merged " << documents.size() << " fuzz shards: " << merged["cases"] << " cases, "
                << (failed ? "failed: " + merged["failure"]["message"].get<std::string>() +
                                 (merged.contains("counterexample") ? " (counterexample in " + merged["counterexample"].get<std::string>() + ")" : "")
                           : std::string("passed"))
                << "\nwrote " << f->output << "\n";
      return failed ? kExitGateFailed : 0;
    }
    const ReportParts parts = merge_shard_documents(documents, f->inputs);
    const AssembledReport assembled = assemble_report(parts);
    write_text_file_atomically(f->output, assembled.document.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
    if (!f->junit.empty()) write_text_file_atomically(f->junit, junit_xml({assembled.verdict}));
    int exit = assembled.verdict.exit_code();
    if (!f->html.empty()) {
      if (const std::string problem = write_report_page(assembled.document, nullptr, f->html, 900); !problem.empty()) {
        std::cerr << "cullcheck: the page has no map: " << problem << "\n";
        exit = std::max(exit, kExitBadInput);
      }
      std::cout << "wrote " << f->html << "\n";
    }
    std::cout << "merged " << f->inputs.size() << " shards: " << parts.verification.oracle.frames_checked << " checked frames\n"
              << summary_table(parts.verification);
    for (const ClaimCheck& c : assembled.claims)
      std::cout << "claim " << c.id << ": " << (c.holds ? "holds" : "REFUTED") << " (" << c.frames_checked << " frames, "
                << c.violations << " violations)\n";
    std::cout << "wrote " << f->output << "\n";
    return exit;
  };
}

}  // namespace cullcheck::cli
