#include "engine/shrinking/view_cell.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "core/elapsed.hpp"
#include "engine/shrinking/circle_tiling.hpp"

namespace cullcheck {
namespace {

// A count as "1.23e+15" (std::to_string of a double prints six decimals; a cast to an integer
// is undefined when it overflows).
std::string count_text(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", v);
  return text;
}

constexpr std::uint32_t kNoIndex = 0xFFFFFFFFu;

}  // namespace

std::string_view cell_sampling_name(CellSampling s) { return s == CellSampling::boundary ? "boundary" : "tiled"; }

CellSampling parse_cell_sampling(std::string_view name) {
  if (name == "boundary") return CellSampling::boundary;
  if (name == "tiled") return CellSampling::tiled;
  throw std::invalid_argument("unknown view-cell sampling '" + std::string(name) + "' (known: boundary, tiled)");
}

std::vector<Vec2> boundary_samples(const std::vector<Vec2>& ring, double epsilon) {
  std::vector<Vec2> out;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Vec2 a = ring[i], d = ring[(i + 1) % ring.size()] - a;
    // Checked before the conversion (NaN or beyond size_t is undefined behaviour); std::max
    // would turn a NaN into 1.
    double count = std::ceil(length(d) / (2.0 * epsilon));
    if (count < 1.0) count = 1.0;
    if (!(count <= static_cast<double>(kMaxSamplesPerEdge)))
      throw std::invalid_argument("view cell: edge " + std::to_string(i) + " needs " + count_text(count) +
                                  " samples at ε = " + std::to_string(epsilon) + " m (at most " +
                                  std::to_string(kMaxSamplesPerEdge) + ")");
    const auto pieces = static_cast<std::size_t>(count);
    for (std::size_t k = 0; k < pieces; ++k) out.push_back(a + d * (static_cast<double>(k) / static_cast<double>(pieces)));
  }
  return out;
}

namespace {

void check_cell(const ViewCell& cell, double epsilon, CellSampling sampling, std::size_t max_samples) {
  const auto& r = cell.ring;
  if (r.size() < 3) throw std::invalid_argument("view cell: needs at least 3 vertices, has " + std::to_string(r.size()));
  double area = 0.0;
  for (std::size_t i = 0; i < r.size(); ++i) {
    const Vec2 a = r[i], b = r[(i + 1) % r.size()], c = r[(i + 2) % r.size()];
    if (!std::isfinite(a.x) || !std::isfinite(a.y)) throw std::invalid_argument("view cell: vertex " + std::to_string(i) + " is not finite");
    if (a == b) throw std::invalid_argument("view cell: vertex " + std::to_string(i) + " is repeated");
    if (cross(b - a, c - b) < 0.0) throw std::invalid_argument("view cell: not convex and counter-clockwise at vertex " + std::to_string((i + 1) % r.size()));
    area += cross(a - r[0], b - r[0]);  // about its first vertex: far-from-origin cells keep their digits
  }
  if (!(area > 0.0)) throw std::invalid_argument("view cell: has no area");
  if (!std::isfinite(cell.eye_height)) throw std::invalid_argument("view cell: eye height is not finite");
  if (!(epsilon > 0.0) || !std::isfinite(epsilon)) throw std::invalid_argument("view cell: ε must be positive and finite");
  // Estimate before generating: perimeter / 2ε boundary samples, area / (1.5·√3·ε²) lattice discs.
  double perimeter = 0.0;
  for (std::size_t i = 0; i < r.size(); ++i) perimeter += length(r[(i + 1) % r.size()] - r[i]);
  const double estimate = sampling == CellSampling::boundary
                              ? perimeter / (2.0 * epsilon) + static_cast<double>(r.size())
                              : 0.5 * area / (1.5 * std::sqrt(3.0) * epsilon * epsilon) + perimeter / epsilon;
  if (estimate > static_cast<double>(max_samples))
    throw std::invalid_argument("view cell: ε = " + std::to_string(epsilon) + " m needs about " +
                                count_text(estimate) + " samples, more than the limit " +
                                std::to_string(max_samples));
}

}  // namespace

std::vector<Vec2> cell_samples(const ViewCell& cell, double epsilon, CellSampling sampling, std::size_t max_samples) {
  check_cell(cell, epsilon, sampling, max_samples);
  return sampling == CellSampling::boundary ? boundary_samples(cell.ring, epsilon)
                                            : CircleTiling{epsilon}.centres_covering(cell.ring);
}

ViewCellPvs::ViewCellPvs(RegionCullingMethod& method, const Scene& scene, std::size_t passive_targets)
    : method_(method), scene_(scene), passive_targets_(passive_targets) {
  for (std::uint32_t b = 0; b < scene.buildings.size(); ++b) index_of_.emplace_back(scene.buildings[b].id, b);
  std::sort(index_of_.begin(), index_of_.end());
  // Ids that are (nearly) the indices, as generated cities' are: a direct table, not a search
  // for each id of each sample's PVS.
  if (!index_of_.empty() && index_of_.back().first < 4 * index_of_.size() + 64) {
    dense_index_of_.assign(index_of_.back().first + 1, kNoIndex);
    for (const auto& [id, b] : index_of_)
      if (dense_index_of_[id] == kNoIndex) dense_index_of_[id] = b;  // the first, as the search finds
  }
}

ViewCellResult ViewCellPvs::compute(const ViewCell& cell, double epsilon, CellSampling sampling, bool carry,
                                    const Camera& camera, Shard shard) {
  const auto start = std::chrono::steady_clock::now();
  std::vector<Vec2> samples = cell_samples(cell, epsilon, sampling);
  ViewCellResult out;
  out.cell_samples = samples.size();
  if (!shard.whole()) {
    std::size_t kept = 0;
    for (std::size_t n = 0; n < samples.size(); ++n)
      if (shard.owns(n)) samples[kept++] = samples[n];
    samples.resize(kept);
  }
  out.samples = samples.size();
  std::vector<char>& known = known_;
  known.assign(scene_.buildings.size(), 0);
  known_passive_.assign(passive_targets_, 0);
  auto mark = [&](ObjectId id) {
    if (id < dense_index_of_.size() && dense_index_of_[id] != kNoIndex) {
      known[dense_index_of_[id]] = 1;
      return;
    }
    const auto it = std::lower_bound(index_of_.begin(), index_of_.end(), std::pair<ObjectId, std::uint32_t>{id, 0});
    known[it->second] = 1;
  };
  Camera eye = camera;
  eye.hfov = kTwoPi;
  eye.yaw = eye.pitch = eye.roll = 0.0;
  for (const Vec2 s : samples) {
    eye.position = {s.x, s.y, cell.eye_height};
    const ViewRegion region{eye, epsilon, 0.0};
    const CullResult r = carry ? method_.cull_region_carrying(region, known, passive_targets_ ? &known_passive_ : nullptr) : method_.cull_region(region);
    out.sample_pvs_size.push_back(r.pvs.size());
    for (ObjectId id : r.pvs) mark(id);
    for (ObjectId id : r.passive) {
      if (id >= known_passive_.size())
        throw std::logic_error("view cell: passive target " + std::to_string(id) + " beyond the " +
                               std::to_string(passive_targets_) + " the view cell was told of");
      known_passive_[id] = 1;
    }
    add_counts(out.stats, r.stats);
  }
  for (std::uint32_t b = 0; b < scene_.buildings.size(); ++b)
    if (known[b]) out.pvs.push_back(scene_.buildings[b].id);
  std::sort(out.pvs.begin(), out.pvs.end());
  for (std::uint32_t t = 0; t < known_passive_.size(); ++t)
    if (known_passive_[t]) out.passive.push_back(t);
  out.stats.cull_ms = ms_since(start);
  return out;
}

}  // namespace cullcheck
