// What the GeoJSON and CityJSON readers share: footprint rings as files give them, made fit for a
// Building; heights from a feature's attributes; the import report's notes.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/formats/import_options.hpp"
#include "core/geometry.hpp"

namespace cullcheck::formats {

// The ring without its closing vertex, repeated vertices and spikes (a vertex where the outline
// goes straight back along the edge it came in on). `changed`: more than the closing vertex went.
std::vector<Vec2> cleaned_ring(std::vector<Vec2> ring, bool& changed);

// Why a cleaned ring cannot be a Building's footprint ("fewer than 3 distinct vertices", "more
// than 4096 vertices", "edges cross or touch", "zero area"), or "" when it can.
std::string footprint_problem(const std::vector<Vec2>& ring);

// A height in metres from `attributes`: the value of --height-attribute, else of
// --storeys-attribute times --storey-height, else of `default_key` (metres); a number or a
// numeric string (nothing after it). nullopt when it is missing, not a number, zero or negative.
std::optional<double> attribute_height(const nlohmann::json& attributes, const FootprintOptions& options,
                                       const std::string& default_key);

// Adds `text` to report.notes while there are fewer than 20; the 21st note is `overflow` (the
// counts still hold every skipped feature).
void add_note(ImportReport& report, const std::string& text, const std::string& overflow);

}  // namespace cullcheck::formats
