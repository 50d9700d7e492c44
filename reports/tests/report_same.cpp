// report_same A.json B.json: exit 0 when two reports are the same but for what is timed
// (without_timings, report.hpp), else 1 and the first place they differ. For shell tests (two
// runs of one seed, merged shards against one run).
#include <fstream>
#include <iostream>
#include <sstream>

#include "reports/report.hpp"

namespace {

nlohmann::json read(const char* path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return nlohmann::json::parse(text.str());
}

// The JSON pointer of the first difference ("" when none).
std::string first_difference(const nlohmann::json& a, const nlohmann::json& b, const std::string& at) {
  if (a.type() != b.type()) return at + " (type)";
  if (a.is_object()) {
    for (const auto& [key, value] : a.items()) {
      if (!b.contains(key)) return at + "/" + key + " (only in the first)";
      if (std::string d = first_difference(value, b[key], at + "/" + key); !d.empty()) return d;
    }
    for (const auto& [key, value] : b.items())
      if (!a.contains(key)) return at + "/" + key + " (only in the second)";
    return "";
  }
  if (a.is_array()) {
    for (std::size_t k = 0; k < a.size() && k < b.size(); ++k)
      if (std::string d = first_difference(a[k], b[k], at + "/" + std::to_string(k)); !d.empty()) return d;
    return a.size() == b.size() ? "" : at + " (length " + std::to_string(a.size()) + " vs " + std::to_string(b.size()) + ")";
  }
  return a == b ? "" : at + ": " + a.dump() + " vs " + b.dump();
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: report_same A.json B.json\n";
    return 2;
  }
  try {
    const std::string d =
        first_difference(cullcheck::without_timings(read(argv[1])), cullcheck::without_timings(read(argv[2])), "");
    if (d.empty()) return 0;
    std::cout << argv[1] << " and " << argv[2] << " differ at " << d.substr(0, 300) << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "report_same: " << e.what() << "\n";
    return 2;
  }
}
