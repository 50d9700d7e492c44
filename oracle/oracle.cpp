#include "oracle/oracle.hpp"

#include <chrono>

namespace cullcheck::oracle {

Oracle::Oracle(const Scene& scene) : scene_(scene), rays_(scene) {}
Oracle::~Oracle() = default;

const ExactVisibility2d& Oracle::exact_2d() const {
  std::call_once(exact_once_, [&] { exact_ = std::make_unique<ExactVisibility2d>(scene_); });
  return *exact_;
}

OracleAnswer Oracle::visible_set(const Camera& camera, const OracleOptions& options, RayLog* log) const {
  const auto start = std::chrono::steady_clock::now();
  OracleAnswer answer;
  const Exact2dApplicability applicability =
      options.allow_exact_2d ? check_exact_2d(scene_, camera) : Exact2dApplicability{false, "exact 2D disabled by options"};
  if (applicability.applies) {
    answer.model = kModelExact2d;
    answer.exact = true;
    answer.exact_2d = exact_2d().visible(camera);
    answer.visible = answer.exact_2d->visible;
  } else {
    answer.model = kModelRaySampling3d;
    answer.sampling = rays_.witness(camera, options.sampling, log);
    answer.visible = answer.sampling->witnessed;
  }
  answer.why = applicability.reason;
  answer.elapsed_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return answer;
}

}  // namespace cullcheck::oracle
