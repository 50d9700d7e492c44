#include "core/formats/footprint_rings.hpp"

#include <cmath>
#include <cstddef>
#include <limits>
#include <locale>
#include <sstream>

#include "core/scene.hpp"
#include "core/scene_io.hpp"

namespace cullcheck::formats {

std::vector<Vec2> cleaned_ring(std::vector<Vec2> ring, bool& changed) {
  changed = false;
  while (ring.size() >= 2 && ring.front() == ring.back()) ring.pop_back();
  for (bool again = true; again && ring.size() >= 3;) {
    again = false;
    for (std::size_t i = 0; i < ring.size() && ring.size() >= 3; ++i) {
      const std::size_t n = ring.size();
      const Vec2 a = ring[(i + n - 1) % n], b = ring[i], c = ring[(i + 1) % n];
      const Vec2 in = b - a, out = c - b;
      const bool repeated = b == c;
      const bool spike = cross(in, out) == 0.0 && dot(in, out) < 0.0;
      if (repeated || spike) {
        ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(i));
        changed = again = true;
        break;
      }
    }
  }
  return ring;
}

std::string footprint_problem(const std::vector<Vec2>& ring) {
  if (ring.size() < 3) return "fewer than 3 distinct vertices";
  if (ring.size() > kMaxFootprintVertices) return "more than 4096 vertices";
  if (!is_simple(ring)) return "edges cross or touch";
  if (!(std::abs(signed_area(ring)) > 0.0)) return "zero area";
  return "";
}

std::optional<double> attribute_height(const nlohmann::json& attributes, const FootprintOptions& o,
                                       const std::string& default_key) {
  const std::string& key = !o.height_attribute.empty() ? o.height_attribute : !o.storeys_attribute.empty() ? o.storeys_attribute : default_key;
  if (!attributes.is_object()) return std::nullopt;
  const auto it = attributes.find(key);
  if (it == attributes.end()) return std::nullopt;
  double v = std::numeric_limits<double>::quiet_NaN();
  if (it->is_number()) {
    v = it->get<double>();
  } else if (it->is_string()) {
    std::istringstream in(it->get_ref<const std::string&>());
    in.imbue(std::locale::classic());
    if (!(in >> v) || !(in >> std::ws).eof()) return std::nullopt;
  }
  if (!o.storeys_attribute.empty() && o.height_attribute.empty()) v *= o.storey_height;
  if (!std::isfinite(v) || !(v > 0.0)) return std::nullopt;
  return v;
}

void add_note(ImportReport& report, const std::string& text, const std::string& overflow) {
  constexpr std::size_t kMaxNotes = 20;  // notes name the first skipped features; the counts hold all
  if (report.notes.size() < kMaxNotes) report.notes.push_back(text);
  else if (report.notes.size() == kMaxNotes) report.notes.push_back(overflow);
}

}  // namespace cullcheck::formats
