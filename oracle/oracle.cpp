#include "oracle/oracle.hpp"

#include <chrono>
#include <stdexcept>
#include <string>

#include "core/elapsed.hpp"

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
  answer.elapsed_seconds = seconds_since(start);
  return answer;
}

const WitnessRecheck& Oracle::recheck_witness(OracleAnswer& answer, ObjectId object, const WitnessRay& ray,
                                              const Camera& camera) const {
  const auto key = std::make_pair(object, ray.source == RaySource::pixel);
  if (const auto found = answer.rechecked.find(key); found != answer.rechecked.end()) return found->second;
  const WitnessRecheck verdict = triangles_.recheck(ray, object, camera);
  ++answer.witness_recheck.checked;
  answer.witness_recheck.dropped += verdict.stands() ? 0 : 1;
  return answer.rechecked.emplace(key, verdict).first->second;
}

const WitnessRecheck& Oracle::confirm_witness(OracleAnswer& answer, ObjectId object, const Camera& camera) const {
  const auto key = std::make_pair(object, false);
  if (const auto found = answer.rechecked.find(key); found != answer.rechecked.end()) return found->second;
  if (!answer.sampling || !answer.sampling->witnesses.count(object))
    throw std::logic_error("Oracle::confirm_witness: the answer has no ray-sampling witness of object " + std::to_string(object));
  OracleResult& sampling = *answer.sampling;
  WitnessRecheck verdict = triangles_.recheck(sampling.witnesses.at(object), object, camera);
  if (!verdict.stands())
    if (const auto further = sampling.further_witnesses.find(object); further != sampling.further_witnesses.end())
      for (const WitnessRay& ray : further->second)
        if (const WitnessRecheck v = triangles_.recheck(ray, object, camera); v.stands()) {
          sampling.witnesses.at(object) = ray;
          verdict = v;
          break;
        }
  ++answer.witness_recheck.checked;
  answer.witness_recheck.dropped += verdict.stands() ? 0 : 1;
  return answer.rechecked.emplace(key, verdict).first->second;
}

}  // namespace cullcheck::oracle
