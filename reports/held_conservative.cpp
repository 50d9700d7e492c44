#include "reports/held_conservative.hpp"

namespace cullcheck {
namespace {

class HeldConservative final : public CullingMethod {
 public:
  explicit HeldConservative(std::unique_ptr<CullingMethod> inner) : inner_(std::move(inner)) {}
  std::string name() const override { return inner_->name(); }
  bool claims_conservative() const override { return true; }
  // Every camera the method answers for: the paper's claim is not limited to some of them.
  bool claims_conservative_for(const Camera&) const override { return true; }
  bool incremental() const override { return inner_->incremental(); }
  std::optional<std::uint64_t> pixel_error_budget() const override { return std::nullopt; }
  void set_frame(std::size_t frame, double time) override { inner_->set_frame(frame, time); }
  bool update_scene(const Scene& present, const std::vector<ObjectId>& appeared, const std::vector<ObjectId>& vanished) override {
    return inner_->update_scene(present, appeared, vanished);
  }
  std::string unsupported_camera(const Camera& camera) const override { return inner_->unsupported_camera(camera); }
  CullResult cull(const Camera& camera) override { return inner_->cull(camera); }

 private:
  std::unique_ptr<CullingMethod> inner_;
};

}  // namespace

std::unique_ptr<CullingMethod> held_conservative(std::unique_ptr<CullingMethod> method) {
  return std::make_unique<HeldConservative>(std::move(method));
}

}  // namespace cullcheck
