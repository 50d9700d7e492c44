// The report page's map (issue 12): one checked frame of one method drawn in plan like the
// papers' figures: the view volume, visible / over-estimated / culled objects, any missed object
// in red with its witness ray. report.json carries the frame as data ("map": the camera, the PVS,
// what the oracle saw and missed, the witness rays), so `cullcheck html` redraws it from the
// report and the scene its replay flags rebuild.
#pragma once

#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "core/scene.hpp"
#include "reports/verification.hpp"

namespace cullcheck::html {

// The run whose snapshot the map shows. `method` given: that run (std::invalid_argument naming
// the runs there are when it is not one of them, or has no checked frame). Otherwise the worst:
// of the runs that missed something, the one whose worst frame missed most (runs that claim to
// be conservative first, as the gate judges them); when none missed anything, `reference` (the
// reference method's worst over-estimate), else the first run with a snapshot. nullptr when no
// run has a checked frame.
const MethodRun* choose_map_run(const PathVerification& v, const std::string& method, const std::string& reference);

// report.json's "map": the run's snapshot as data, and why it was chosen (`chosen_by`).
nlohmann::json map_json(const MethodRun& run, const std::string& chosen_by);

// The plan box the map shows: the eye, every object the oracle saw or the method missed, and the
// witness rays, at least `min_half_span` metres around the eye.
Box2 map_extent(const Scene& scene, const nlohmann::json& map, double min_half_span = 60.0);

// The map of report.json's "map" as PNG bytes, its longer side `size_px` pixels. InputError
// naming the field when the section is malformed or names an object the scene does not have.
std::string map_png(const Scene& scene, const nlohmann::json& map, int size_px = 900);

}  // namespace cullcheck::html
