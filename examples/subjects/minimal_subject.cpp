// The smallest useful subject (README "The subject protocol"): culls each object's bounding box
// against the view volume in clip space (all 8 corners outside one plane), so it is conservative.
#include <nlohmann/json.hpp>
#include <iostream>
using nlohmann::json;
int main() {
  std::string line;
  std::getline(std::cin, line);
  const json objects = json::parse(line)["scene"]["objects"];
  std::cout << R"({"type":"ready","name":"minimal-box","claims":"conservative","projections":["perspective","orthographic"]})" << std::endl;
  while (std::getline(std::cin, line)) {
    const json frame = json::parse(line);
    if (frame["type"] != "frame") break;
    const json &v = frame["view"], &p = frame["projection"];
    json m = json::array(), ids = json::array();  // m = projection * view
    for (int r = 0; r < 4; ++r) for (int c = 0; c < 4; ++c) { double s = 0; for (int k = 0; k < 4; ++k) s += double(p[r][k]) * double(v[k][c]); m[r][c] = s; }
    for (const json& o : objects) {
      int outside[6] = {0, 0, 0, 0, 0, 0};  // per clip plane: corners beyond it
      for (int i = 0; i < 8; ++i) {
        double q[3] = {o["bounds"][i & 1][0], o["bounds"][(i >> 1) & 1][1], o["bounds"][(i >> 2) & 1][2]}, x[4];
        for (int r = 0; r < 4; ++r) x[r] = double(m[r][0]) * q[0] + double(m[r][1]) * q[1] + double(m[r][2]) * q[2] + double(m[r][3]);
        for (int a = 0; a < 3; ++a) outside[2 * a] += x[a] < -x[3], outside[2 * a + 1] += x[a] > x[3];
      }
      bool culled = false;
      for (int k : outside) culled = culled || k == 8;
      if (!culled) ids.push_back(o["id"]);
    }
    std::cout << json{{"type", "visible"}, {"frame", frame["frame"]}, {"ids", ids}}.dump() << std::endl;
  }
}
