// cullcheck html: report.json as the report page, one self-contained HTML file (no network).
#include <iostream>
#include <memory>

#include "apps/cullcheck/flags.hpp"
#include "apps/cullcheck/page_writer.hpp"
#include "apps/cullcheck/subcommands.hpp"
#include "core/errors.hpp"
#include "core/scene_io.hpp"
#include "reports/html/frame_map.hpp"
#include "reports/html/report_page.hpp"

namespace cullcheck::cli {

std::string write_report_page(const nlohmann::json& report, const Scene* scene, const std::string& path, int map_px) {
  html::PageMap map;
  if (report.contains("map")) {
    try {
      std::optional<Scene> rebuilt;
      if (!scene) {
        const auto flags = report.contains("scene") ? report["scene"].value("replay_flags", std::string()) : std::string();
        if (flags.empty()) throw InputError("report", "scene.replay_flags", "is missing: the map's scene cannot be rebuilt");
        CLI::App parser;
        SceneFlags scene_flags;
        scene_flags.add(parser);
        try {
          parser.parse(flags, false);
        } catch (const CLI::ParseError& e) {
          throw InputError("report", "scene.replay_flags", "cannot be read (" + std::string(e.what()) + "): " + flags);
        }
        rebuilt = scene_flags.source.load();
        scene = &*rebuilt;
      }
      map.png = html::map_png(*scene, report["map"], map_px);
    } catch (const std::exception& e) {
      map.problem = e.what();
    }
  }
  write_text_file_atomically(path, html::report_page(report, map));
  return map.problem;
}

Runner add_html(CLI::App& app) {
  struct Flags {
    SceneFlags scene;
    std::string input, output = "report.html";
    int map_px = 900;
  };
  auto f = std::make_shared<Flags>();
  CLI::App* sub = app.add_subcommand(
      "html", "The report page of a report.json: one self-contained HTML file with the summary, the claims ledger, plots and the map");
  sub->add_option("report", f->input, "report.json written by `cullcheck report`")->required();
  sub->add_option("--output,-o", f->output, "Page to write")->capture_default_str();
  sub->add_option("--map-size", f->map_px, "Pixels along the map's longer side")->capture_default_str()->check(CLI::Range(64, 8192));
  f->scene.add(*sub);
  return [f, sub] {
    const nlohmann::json report = parse_json_flag(read_text_file(f->input), f->input);
    if (!report.is_object() || !report.contains("schema_version"))
      throw InputError("file " + f->input, "schema_version", "is missing: not a report written by cullcheck");
    // Scene flags given here replace the report's (a scene file moved since the run).
    bool scene_given = false;
    for (const char* name : {"--generator", "--seed", "--params", "--scene"}) scene_given = scene_given || sub->count(name) > 0;
    std::optional<Scene> scene;
    if (scene_given) scene = f->scene.source.load();
    const std::string problem = write_report_page(report, scene ? &*scene : nullptr, f->output, f->map_px);
    std::cout << "wrote " << f->output << "\n";
    if (!problem.empty()) {
      std::cerr << "cullcheck: the page has no map: " << problem
                << " (pass the scene flags the report was made with, e.g. --scene FILE)\n";
      return kExitBadInput;
    }
    return 0;
  };
}

}  // namespace cullcheck::cli
