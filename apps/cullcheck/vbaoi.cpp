// cullcheck vbaoi: the navigable-region graph (PVSo, PVSn, SNs) and the simulated clients with
// VbAoI and its baselines, channel grouping checked against the oracle; exit 1 on a violation.
#include <iostream>
#include <memory>

#include "apps/cullcheck/flags.hpp"
#include "apps/cullcheck/subcommands.hpp"
#include "core/scene_io.hpp"
#include "reports/vbaoi.hpp"

namespace cullcheck::cli {

Runner add_vbaoi(CLI::App& app) {
  struct Flags {
    SceneFlags scene;
    MethodFlags tuning;
    VbaoiFlags vbaoi;
    std::string output;
  };
  auto f = std::make_shared<Flags>();
  CLI::App* sub = app.add_subcommand(
      "vbaoi", "VbAoI (thesis ch. 5): build the navigable-region graph (PVSo, PVSn, SNs), simulate clients with VbAoI, "
               "broadcast, neighbours-only and circular AoI, check channel grouping against the oracle; exit 1 on a "
               "violation");
  f->scene.add(*sub);
  f->tuning.add(*sub);
  f->vbaoi.add(*sub, {10, 100});
  sub->add_option("--output,-o", f->output, "Also write the section as JSON to this file");
  return [f] {
    const Scene scene = f->scene.source.load();
    VbaoiOptions options = f->vbaoi.resolved();
    options.graph.method_options = f->tuning.options;
    const nlohmann::json section = vbaoi_report(scene, f->scene.source, options);
    std::cout << vbaoi_table(section);
    if (!f->output.empty()) write_text_file_atomically(f->output, section.dump(2) + "\n");
    const std::size_t violations = vbaoi_gate_violations(section);
    if (violations > 0)
      for (const auto& run : section["runs"]) std::cout << "replay: " << run["replay"].get<std::string>() << "\n";
    return violations == 0 ? 0 : kExitGateFailed;
  };
}

}  // namespace cullcheck::cli
