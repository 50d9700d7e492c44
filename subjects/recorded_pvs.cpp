#include "subjects/recorded_pvs.hpp"

#include <fstream>

#include "subjects/subject_error.hpp"
#include "subjects/subject_method.hpp"

namespace cullcheck {

RecordedPvsMethod::RecordedPvsMethod(const Scene& scene, const std::string& path, const protocol::Claim& claim, std::string name)
    : path_(path), name_(name.empty() ? program_name(path) : name), claim_(claim) {
  const bool named = !name.empty();  // a given name beats the file's ready line
  const std::string label = "recorded PVS file " + path;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SubjectError(SubjectError::Kind::failed_to_start, label, SubjectError::kHandshake, "cannot be opened for reading");
  const std::vector<ObjectId> known = scene.ids();
  std::string line;
  for (std::size_t number = 1; std::getline(in, line); ++number) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const std::string where = label + " line " + std::to_string(number);
    const nlohmann::json message = nlohmann::json::parse(line, nullptr, false);
    if (message.is_discarded() || !message.is_object())
      throw SubjectError(SubjectError::Kind::garbage, where, SubjectError::kHandshake, "is not a JSON object");
    if (message.value("type", nlohmann::json()) == "ready") {
      if (number != 1 && !frames_.empty())
        throw SubjectError(SubjectError::Kind::protocol, where, SubjectError::kHandshake, "a ready line must come first");
      if (auto n = message.find("name"); n != message.end() && n->is_string() && !named) name_ = *n;
      if (message.contains("claims")) claim_ = protocol::parse_claim(message, where, SubjectError::kHandshake);
      continue;
    }
    const auto f = message.find("frame");
    if (f == message.end() || !f->is_number_unsigned())
      throw SubjectError(SubjectError::Kind::protocol, where, SubjectError::kHandshake, R"("frame" must be an integer >= 0)");
    const std::size_t frame = f->get<std::size_t>();
    if (frames_.count(frame))
      throw SubjectError(SubjectError::Kind::protocol, where, static_cast<std::int64_t>(frame), "gives this frame a second time");
    frames_[frame] = protocol::parse_visible(message, where, frame, known).ids;
  }
}

RecordedPvsMethod::RecordedPvsMethod(const Scene& scene, std::map<std::size_t, std::vector<ObjectId>> frames,
                                     const protocol::Claim& claim, std::string name)
    : path_("(given)"), name_(std::move(name)), claim_(claim) {
  const std::vector<ObjectId> known = scene.ids();
  for (auto& [frame, ids] : frames) {
    nlohmann::json message = {{"frame", frame}, {"ids", ids}};
    frames_[frame] = protocol::parse_visible(message, "visible set " + name_, frame, known).ids;
  }
}

CullResult RecordedPvsMethod::cull(const Camera& /*camera*/) {
  const auto it = frames_.find(frame_);
  if (it == frames_.end())
    throw SubjectError(SubjectError::Kind::protocol, "recorded PVS file " + path_, static_cast<std::int64_t>(frame_),
                       "holds no line for this frame");
  CullResult result;
  result.pvs = it->second;
  return result;
}

}  // namespace cullcheck
