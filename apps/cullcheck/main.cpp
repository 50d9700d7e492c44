// cullcheck: the command-line program. Thin: it parses flags and calls the libraries; each
// subcommand lives in its own file (subcommands.hpp).
//
// Exit codes: 0 success; 1 the gate failed (a method or subject that claims to be conservative
// culled something the oracle saw, or an approximate one exceeded its pixel budget); 2 bad input
// (one line on stderr naming the object and field; an outside subject that crashes, hangs or
// answers garbage is bad input too); 3 an internal error (a bug: please report it with the
// command line), or cullcheck ran out of memory: either way no verdict was reached.
#include <CLI/CLI.hpp>

#include <iostream>
#include <new>
#include <stdexcept>
#include <utility>
#include <vector>

#include "apps/cullcheck/flags.hpp"
#include "apps/cullcheck/subcommands.hpp"
#include "core/errors.hpp"
#include "core/progress.hpp"
#include "subjects/subject_error.hpp"

int main(int argc, char** argv) {
  namespace cli = cullcheck::cli;
  CLI::App app{"cullcheck: urban occlusion culling held to an oracle (Embree + CGAL) on seeded cities"};
  app.require_subcommand(1);
  // --quiet anywhere on the line (fallthrough: after the subcommand too) turns progress off.
  bool quiet = false;
  app.add_flag("--quiet,-q", quiet, "No progress lines on stderr (shown only when stderr is a terminal, for runs over 2 s)");
  app.fallthrough();
  const std::vector<std::pair<CLI::App*, cli::Runner>> subcommands = [&] {
    std::vector<std::pair<CLI::App*, cli::Runner>> out;
    for (auto add : {cli::add_generate, cli::add_cull, cli::add_verify, cli::add_region, cli::add_cell, cli::add_vbaoi,
                     cli::add_report, cli::add_gate, cli::add_fuzz, cli::add_html, cli::add_merge, cli::add_radar}) {
      cli::Runner run = add(app);
      out.emplace_back(app.get_subcommands({}).back(), std::move(run));
    }
    return out;
  }();

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : cli::kExitBadInput;
  }

  if (quiet) cullcheck::Progress::set_mode(cullcheck::Progress::Mode::never);
  try {
    for (const auto& [sub, run] : subcommands)
      if (*sub) return run();
  } catch (const cullcheck::InputError& e) {
    std::cerr << "cullcheck: " << e.what() << "\n";
    return cli::kExitBadInput;
  } catch (const cullcheck::SubjectError& e) {  // an outside program under test is bad input too
    std::cerr << "cullcheck: " << e.what() << "\n";
    return cli::kExitBadInput;
  } catch (const std::invalid_argument& e) {
    std::cerr << "cullcheck: " << e.what() << "\n";
    return cli::kExitBadInput;
  } catch (const std::bad_alloc& e) {  // no verdict either way; not a gate failure, not bad input
    std::cerr << "cullcheck: internal error: out of memory (" << e.what() << "): no verdict was reached\n";
    return cli::kExitInternalError;
  } catch (const std::exception& e) {
    std::cerr << "cullcheck: internal error: " << e.what() << "\n";
    return cli::kExitInternalError;
  }
  return 0;
}
