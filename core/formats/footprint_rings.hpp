// Footprint rings as files give them, made fit for a Building (GeoJSON and CityJSON readers).
#pragma once

#include <vector>

#include "core/geometry.hpp"

namespace cullcheck::formats {

// The ring without its closing vertex, repeated vertices and spikes (a vertex where the outline
// goes straight back along the edge it came in on). `changed`: more than the closing vertex went.
std::vector<Vec2> cleaned_ring(std::vector<Vec2> ring, bool& changed);

}  // namespace cullcheck::formats
