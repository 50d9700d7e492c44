// The report page's file (reports/html/report_page.hpp), written by `report --html` and by
// `cullcheck html`: the page from report.json, its map drawn on the report's scene.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "core/scene.hpp"

namespace cullcheck::cli {

// Writes the page to `path` atomically. The map is drawn on `scene`; when that is null the scene
// is rebuilt from the report's scene.replay_flags. Returns "" or, when the map could not be
// drawn (the scene cannot be rebuilt, or is not the report's), why: the page is written anyway
// and says so in the map's place.
std::string write_report_page(const nlohmann::json& report, const Scene* scene, const std::string& path, int map_px);

}  // namespace cullcheck::cli
