// cullcheck merge: the shard files of one run (`report --shard K/N`, `verify --shard K/N`) joined
// into the report of the whole run, the one an unsharded run writes (timings aside).
#include <iostream>
#include <memory>

#include "apps/cullcheck/flags.hpp"
#include "apps/cullcheck/page_writer.hpp"
#include "apps/cullcheck/subcommands.hpp"
#include "core/errors.hpp"
#include "core/scene_io.hpp"
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
      "merge", "Join the N shard files of one run (written with --shard K/N) into the report of the whole run");
  sub->add_option("shards", f->inputs, "Every shard file of the run, in any order")->required();
  sub->add_option("--output,-o", f->output, "Report file to write")->capture_default_str();
  sub->add_option("--html", f->html, "Also write the report page (its map's scene is rebuilt from the report's scene flags)");
  sub->add_option("--junit", f->junit, "Also write the gate's checks as JUnit XML");
  return [f] {
    std::vector<nlohmann::json> documents;
    for (const std::string& input : f->inputs) documents.push_back(parse_json_flag(read_text_file(input), input));
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
