// The README's minimal subject: keeps every object whose bounding box is not wholly beyond one
// clip plane of projection * view (conservative). Build: g++ -std=c++20 minimal_subject.cpp
#include <algorithm>
#include <iostream>
#include <nlohmann/json.hpp>
int main() {
  using nlohmann::json;
  std::string line;
  std::getline(std::cin, line);
  const json objects = json::parse(line)["scene"]["objects"];
  std::cout << R"({"type":"ready","name":"minimal-box","claims":"conservative","projections":["perspective","orthographic"]})" << std::endl;
  for (json f; std::getline(std::cin, line) && (f = json::parse(line))["type"] == "frame";) {
    double m[4][4] = {};  // m = projection * view
    for (int r = 0; r < 16; ++r) for (int k = 0; k < 4; ++k) m[r / 4][r % 4] += f["projection"][r / 4][k].get<double>() * f["view"][k][r % 4].get<double>();
    json ids = json::array();
    for (const json& o : objects) {
      int beyond[6] = {};  // corners beyond each clip plane: -w <= x, y, z <= w
      for (int i = 0; i < 8; ++i) {
        double p[4] = {o["bounds"][i & 1][0], o["bounds"][i >> 1 & 1][1], o["bounds"][i >> 2][2], 1.0}, c[4] = {};
        for (int r = 0; r < 16; ++r) c[r / 4] += m[r / 4][r % 4] * p[r % 4];
        for (int a = 0; a < 3; ++a) beyond[2 * a] += c[a] < -c[3], beyond[2 * a + 1] += c[a] > c[3];
      }
      if (std::count(beyond, beyond + 6, 8) == 0) ids.push_back(o["id"]);
    }
    std::cout << json{{"type", "visible"}, {"frame", f["frame"]}, {"ids", ids}}.dump() << std::endl;
  }
}
