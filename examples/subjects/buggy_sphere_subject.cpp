// A plausible but buggy culler, for the fuzzer to catch (README "Fuzzing an outside program"):
// bounding spheres against the six planes of the view volume, extracted from projection * view
// (Gribb and Hartmann's method). The bug: each sphere's radius is half the box's LARGEST SIDE
// instead of half its diagonal, so the corners of every box stick out of its sphere and an
// object whose corner alone reaches into the view is culled. It claims to be conservative.
// Nothing else is wrong: on most frames of a street walk it agrees with frustum culling.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <vector>

int main() {
  using nlohmann::json;
  std::ios::sync_with_stdio(false);
  struct Sphere {
    json id;
    double c[3], r;
  };
  std::string line;
  if (!std::getline(std::cin, line)) return 1;
  const json hello = json::parse(line);
  std::vector<Sphere> spheres;
  for (const json& o : hello["scene"]["objects"]) {
    const json& b = o["bounds"];
    Sphere s{o["id"], {}, 0.0};
    for (int a = 0; a < 3; ++a) {
      s.c[a] = (b[0][a].get<double>() + b[1][a].get<double>()) / 2;
      s.r = std::max(s.r, (b[1][a].get<double>() - b[0][a].get<double>()) / 2);  // the bug: not the half diagonal
    }
    spheres.push_back(s);
  }
  std::cout << R"({"type":"ready","name":"buggy-sphere","claims":"conservative","projections":["perspective","orthographic"]})"
            << std::endl;
  while (std::getline(std::cin, line)) {
    const json frame = json::parse(line);
    if (frame["type"] != "frame") break;
    double m[4][4];
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) {
        m[r][c] = 0;
        for (int k = 0; k < 4; ++k) m[r][c] += frame["projection"][r][k].get<double>() * frame["view"][k][c].get<double>();
      }
    double planes[6][4];  // row 3 +- row a: inside when a.x + b.y + c.z + d >= 0
    for (int a = 0; a < 3; ++a)
      for (int s = 0; s < 2; ++s)
        for (int k = 0; k < 4; ++k) planes[2 * a + s][k] = m[3][k] + (s ? -m[a][k] : m[a][k]);
    json ids = json::array();
    for (const Sphere& s : spheres) {
      bool inside = true;
      for (const auto& p : planes) {
        const double n = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
        if ((p[0] * s.c[0] + p[1] * s.c[1] + p[2] * s.c[2] + p[3]) / n < -s.r) inside = false;
      }
      if (inside) ids.push_back(s.id);
    }
    std::cout << json{{"type", "visible"}, {"frame", frame["frame"]}, {"ids", ids}}.dump() << std::endl;
  }
  return 0;
}
