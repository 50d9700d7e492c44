// An outside culling system's per-frame visible sets read from a file, as a CullingMethod: for
// systems that dump what they drew rather than answer over the protocol
// (`cullcheck gate --pvs results.jsonl`).
//
// The file holds JSON lines. An optional first line declares the system:
//   {"type":"ready","name":"my-culler","claims":"conservative"}   (or approximate + pixel_error_budget)
// then one line per frame, in any order, like the protocol's answers:
//   {"frame":0,"ids":[3,17,42]}                                    ("type":"visible" optional)
// A frame asked for but missing, a frame given twice, an unknown id or a malformed line is a
// SubjectError naming the line or the frame.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "engine/method.hpp"
#include "subjects/protocol.hpp"

namespace cullcheck {

class RecordedPvsMethod final : public CullingMethod {
 public:
  // `claim` is used when the file has no ready line (the command line's --claims); a ready line's
  // claim overrides it, and its name is used unless `name` is given.
  RecordedPvsMethod(const Scene& scene, const std::string& path, const protocol::Claim& claim, std::string name = "");
  // Visible sets given directly (`gate --visible IDS` for one camera): ids checked against the scene.
  RecordedPvsMethod(const Scene& scene, std::map<std::size_t, std::vector<ObjectId>> frames, const protocol::Claim& claim,
                    std::string name);

  std::string name() const override { return "recorded:" + name_; }
  bool claims_conservative() const override { return claim_.conservative; }
  std::optional<std::uint64_t> pixel_error_budget() const override { return claim_.pixel_error_budget; }
  std::string unsupported_camera(const Camera& /*camera*/) const override { return ""; }
  void set_frame(std::size_t frame, double /*time_seconds*/) override { frame_ = frame; }
  CullResult cull(const Camera& camera) override;

  std::size_t frames_recorded() const { return frames_.size(); }
  const std::string& path() const { return path_; }

 private:
  std::string path_, name_;
  protocol::Claim claim_;
  std::map<std::size_t, std::vector<ObjectId>> frames_;
  std::size_t frame_ = 0;
};

}  // namespace cullcheck
