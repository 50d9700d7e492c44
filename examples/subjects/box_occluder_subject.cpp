// A second plausible but buggy culler: frustum culling by bounding boxes (correct), then
// occlusion culling with every object's bounding box taken as a solid occluder (the bug). An
// object is culled when the segment from the eye to each corner of its box passes through the
// box of one nearer object. That is exact for solid boxes (the region a convex occluder hides
// from a point is convex), and wrong wherever an object does not fill its box: a wall with a
// door or window, an arcade open at street level, an L- or U-shaped building. It claims to be
// conservative. The fuzzer must find the openings and the L-shapes on its own.
#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <vector>

namespace {

using Vec = std::array<double, 3>;
struct Box {
  nlohmann::json id;
  Vec lo, hi;
};

// Whether the segment from a to b meets the closed box (slab test).
bool segment_meets(const Vec& a, const Vec& b, const Box& box) {
  double t0 = 0.0, t1 = 1.0;
  for (int k = 0; k < 3; ++k) {
    const double d = b[k] - a[k];
    if (std::abs(d) < 1e-12) {
      if (a[k] < box.lo[k] || a[k] > box.hi[k]) return false;
      continue;
    }
    double u = (box.lo[k] - a[k]) / d, v = (box.hi[k] - a[k]) / d;
    if (u > v) std::swap(u, v);
    t0 = std::max(t0, u), t1 = std::min(t1, v);
    if (t0 > t1) return false;
  }
  return true;
}

bool contains(const Box& box, const Vec& p) {
  for (int k = 0; k < 3; ++k)
    if (p[k] < box.lo[k] || p[k] > box.hi[k]) return false;
  return true;
}

}  // namespace

int main() {
  using nlohmann::json;
  std::ios::sync_with_stdio(false);
  std::string line;
  if (!std::getline(std::cin, line)) return 1;
  const json hello = json::parse(line);
  std::vector<Box> boxes;
  for (const json& o : hello["scene"]["objects"])
    boxes.push_back({o["id"], {o["bounds"][0][0], o["bounds"][0][1], o["bounds"][0][2]}, {o["bounds"][1][0], o["bounds"][1][1], o["bounds"][1][2]}});
  std::cout << R"({"type":"ready","name":"box-occluders","claims":"conservative"})" << std::endl;
  while (std::getline(std::cin, line)) {
    const json frame = json::parse(line);
    if (frame["type"] != "frame") break;
    double m[4][4];
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) {
        m[r][c] = 0;
        for (int k = 0; k < 4; ++k) m[r][c] += frame["projection"][r][k].get<double>() * frame["view"][k][c].get<double>();
      }
    const Vec eye{frame["camera"]["position"][0], frame["camera"]["position"][1], frame["camera"]["position"][2]};
    std::vector<const Box*> in_view;
    for (const Box& b : boxes) {
      int outside[6] = {0, 0, 0, 0, 0, 0};
      for (int i = 0; i < 8; ++i) {
        const Vec q{i & 1 ? b.hi[0] : b.lo[0], i & 2 ? b.hi[1] : b.lo[1], i & 4 ? b.hi[2] : b.lo[2]};
        double x[4];
        for (int r = 0; r < 4; ++r) x[r] = m[r][0] * q[0] + m[r][1] * q[1] + m[r][2] * q[2] + m[r][3];
        for (int a = 0; a < 3; ++a) outside[2 * a] += x[a] < -x[3], outside[2 * a + 1] += x[a] > x[3];
      }
      if (std::none_of(std::begin(outside), std::end(outside), [](int k) { return k == 8; })) in_view.push_back(&b);
    }
    json ids = json::array();
    for (const Box* b : in_view) {
      bool hidden = false;
      for (const Box* occluder : in_view) {
        if (occluder == b || contains(*occluder, eye)) continue;
        bool all = true;
        for (int i = 0; i < 8 && all; ++i) {
          const Vec q{i & 1 ? b->hi[0] : b->lo[0], i & 2 ? b->hi[1] : b->lo[1], i & 4 ? b->hi[2] : b->lo[2]};
          all = segment_meets(eye, q, *occluder) && !contains(*occluder, q);
        }
        if (all) {
          hidden = true;
          break;
        }
      }
      if (!hidden) ids.push_back(b->id);
    }
    std::cout << json{{"type", "visible"}, {"frame", frame["frame"]}, {"ids", ids}}.dump() << std::endl;
  }
  return 0;
}
