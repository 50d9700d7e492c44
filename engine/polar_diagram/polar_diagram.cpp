#include "engine/polar_diagram/polar_diagram.hpp"

#include <algorithm>
#include <numeric>

#include "engine/polar_diagram/exact_sign.hpp"

namespace cullcheck::polar {

const char* to_string(DiagramKind kind) {
  switch (kind) {
    case DiagramKind::east_plus: return "East+";
    case DiagramKind::east_minus: return "East-";
    case DiagramKind::west_plus: return "West+";
    case DiagramKind::west_minus: return "West-";
  }
  return "?";
}

Vec2 PolarDiagram::local(Vec2 v) const {
  switch (kind_) {
    case DiagramKind::east_plus: return v;
    case DiagramKind::east_minus: return {v.x, -v.y};   // clockwise from east = counter-clockwise, mirrored
    case DiagramKind::west_plus: return {-v.x, -v.y};   // counter-clockwise from west = East+ turned by pi
    case DiagramKind::west_minus: return {-v.x, v.y};   // clockwise from west = East+ mirrored in x
  }
  return v;
}

PolarDiagram::PolarDiagram(const std::vector<Vec2>& vertices, DiagramKind kind) : kind_(kind) {
  std::vector<std::uint32_t> order(vertices.size());
  std::iota(order.begin(), order.end(), 0u);
  std::vector<Vec2> loc(vertices.size());
  for (std::size_t i = 0; i < vertices.size(); ++i) loc[i] = local(vertices[i]);
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    if (loc[a].y != loc[b].y) return loc[a].y > loc[b].y;
    if (loc[a].x != loc[b].x) return loc[a].x > loc[b].x;
    return a < b;
  });
  sorted_.reserve(order.size());
  for (std::uint32_t i : order) sorted_.push_back(loc[i]);
  original_ = std::move(order);

  while (leaves_ < sorted_.size()) leaves_ *= 2;
  chain_begin_.assign(2 * leaves_, 0);
  chain_end_.assign(2 * leaves_, 0);
  // Each node's right-hand chain: its vertices from low to high (ties in y from left to right,
  // so the chain starts at the lowest row's right end and ends at the top row's right end),
  // keeping left turns only. A query point below them all sees its tangent point on it.
  std::vector<std::uint32_t> chain;
  for (std::size_t node = 1; node < 2 * leaves_; ++node) {
    std::size_t depth = 0;
    while ((std::size_t{1} << (depth + 1)) <= node) ++depth;
    const std::size_t width = leaves_ >> depth;
    const std::size_t lo = (node - (std::size_t{1} << depth)) * width;
    const std::size_t hi = std::min(lo + width, sorted_.size());
    chain_begin_[node] = static_cast<std::uint32_t>(chains_.size());
    chain.clear();
    for (std::size_t i = hi; i-- > lo;) {
      while (chain.size() >= 2 && orient(sorted_[chain[chain.size() - 2]], sorted_[chain.back()], sorted_[i]) <= 0)
        chain.pop_back();
      chain.push_back(static_cast<std::uint32_t>(i));
    }
    chains_.insert(chains_.end(), chain.begin(), chain.end());
    chain_end_[node] = static_cast<std::uint32_t>(chains_.size());
  }
}

std::uint32_t PolarDiagram::candidate(std::size_t node, Vec2 p) const {
  // The first chain vertex whose successor does not turn clockwise from it as seen from p.
  std::size_t lo = chain_begin_[node], hi = chain_end_[node] - 1;
  while (lo < hi) {
    const std::size_t mid = (lo + hi) / 2;
    if (orient(p, sorted_[chains_[mid]], sorted_[chains_[mid + 1]]) >= 0)
      hi = mid;
    else
      lo = mid + 1;
  }
  return chains_[lo];
}

std::int64_t PolarDiagram::first_vertex(Vec2 world) const {
  const Vec2 p = local(world);
  // Vertices strictly above p form a prefix of sorted_.
  const std::size_t above = static_cast<std::size_t>(
      std::partition_point(sorted_.begin(), sorted_.end(), [&](Vec2 v) { return v.y > p.y; }) - sorted_.begin());
  std::int64_t best = -1;
  auto consider = [&](std::size_t node) {
    if (chain_begin_[node] == chain_end_[node]) return;
    const std::uint32_t c = candidate(node, p);
    if (best < 0) {
      best = c;
      return;
    }
    const Vec2 b = sorted_[static_cast<std::size_t>(best)], v = sorted_[c];
    const int turn = orient(p, b, v);
    if (turn < 0 || (turn == 0 && v.y < b.y)) best = c;  // smaller angle, or the same and nearer
  };
  for (std::size_t l = leaves_, r = leaves_ + above; l < r; l /= 2, r /= 2) {
    if (l & 1) consider(l++);
    if (r & 1) consider(--r);
  }
  return best < 0 ? -1 : static_cast<std::int64_t>(original_[static_cast<std::size_t>(best)]);
}

std::vector<Vec2> footprint_vertices(const Scene& scene) {
  std::vector<Vec2> out;
  for (const Building& b : scene.buildings) out.insert(out.end(), b.footprint.begin(), b.footprint.end());
  return out;
}

PolarDiagrams::PolarDiagrams(const std::vector<Vec2>& vertices) {
  for (DiagramKind k : {DiagramKind::east_plus, DiagramKind::east_minus, DiagramKind::west_plus, DiagramKind::west_minus})
    diagrams.emplace_back(vertices, k);
}

}  // namespace cullcheck::polar
