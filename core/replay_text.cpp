#include "core/replay_text.hpp"

#include <sstream>

#include "core/scene_io.hpp"

namespace cullcheck {

std::string round_trip_text(double value) {
  std::ostringstream out;
  out.precision(17);
  out << value;
  return out.str();
}

std::string shell_quote(const std::string& text) {
  std::string quoted = "'";
  for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

std::string camera_arg(const Camera& camera) {
  std::string text = camera_to_json_text(camera);
  if (!text.empty() && text.back() == '\n') text.pop_back();
  return shell_quote(text);
}

std::string ids_text(const std::vector<ObjectId>& ids) {
  std::string out = "[";
  for (ObjectId id : ids) out += (out.size() > 1 ? "," : "") + std::to_string(id);
  return out + "]";
}

}  // namespace cullcheck
