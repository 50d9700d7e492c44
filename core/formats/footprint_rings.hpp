// Footprint rings as files give them, made fit for a Building (GeoJSON and CityJSON readers).
#pragma once

#include <string>
#include <vector>

#include "core/geometry.hpp"

namespace cullcheck::formats {

// The ring without its closing vertex, repeated vertices and spikes (a vertex where the outline
// goes straight back along the edge it came in on). `changed`: more than the closing vertex went.
std::vector<Vec2> cleaned_ring(std::vector<Vec2> ring, bool& changed);

// Why a cleaned ring cannot be a Building's footprint ("fewer than 3 distinct vertices", "more
// than 4096 vertices", "edges cross or touch", "zero area"), or "" when it can.
std::string footprint_problem(const std::vector<Vec2>& ring);

}  // namespace cullcheck::formats
