#include "generators/scene_timeline_gen.hpp"

#include <algorithm>
#include <cmath>

#include "generators/param_checks.hpp"
#include "generators/random.hpp"

namespace cullcheck::generators {
namespace {

// `k` of `pool` drawn without replacement (a partial Fisher-Yates shuffle), ascending.
std::vector<ObjectId> draw(std::vector<ObjectId> pool, std::size_t k, Random& rng) {
  k = std::min(k, pool.size());
  for (std::size_t i = 0; i < k; ++i)
    std::swap(pool[i], pool[static_cast<std::size_t>(rng.uniform_int(static_cast<std::int64_t>(i), static_cast<std::int64_t>(pool.size() - 1)))]);
  pool.resize(k);
  std::sort(pool.begin(), pool.end());
  return pool;
}

std::vector<ObjectId> minus(const std::vector<ObjectId>& a, const std::vector<ObjectId>& b) {
  std::vector<ObjectId> out;
  std::set_difference(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(out));
  return out;
}

}  // namespace

std::vector<SceneEvent> scene_timeline(const Scene& scene, std::size_t frames, const TimelineParams& params, std::uint64_t seed) {
  const ParamChecks check("path", "timeline");
  check.in_range("every", params.every, 1, 1 << 30);
  check.in_range("churn", params.churn, 0.0, 0.5);
  check.in_range("late", params.late, 0.0, 0.5);
  std::vector<ObjectId> ids = scene.ids();
  std::sort(ids.begin(), ids.end());
  Random rng = Random::stream(seed, 0x74696d656c696e65ULL);  // "timeline"
  const auto share = [&](double s, std::size_t of) { return static_cast<std::size_t>(std::llround(s * static_cast<double>(of))); };
  std::vector<ObjectId> absent = draw(ids, share(params.late, ids.size()), rng);
  std::vector<SceneEvent> events;
  for (std::size_t f = static_cast<std::size_t>(params.every); f < frames; f += static_cast<std::size_t>(params.every)) {
    SceneEvent e;
    e.frame = f;
    e.appear = absent;  // everything absent comes back...
    const std::vector<ObjectId> present = minus(ids, absent);
    // ...and a fresh share of what was present vanishes (an object never does both at once).
    e.vanish = draw(present, std::max<std::size_t>(params.churn > 0 ? 1 : 0, share(params.churn, present.size())), rng);
    absent = e.vanish;
    if (!e.appear.empty() || !e.vanish.empty()) events.push_back(std::move(e));
  }
  return events;
}

}  // namespace cullcheck::generators
