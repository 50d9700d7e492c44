#include "reports/claims.hpp"
#include "core/elapsed.hpp"
#include "core/parallel_indices.hpp"
#include "core/progress.hpp"

#include <algorithm>
#include <chrono>
#include <exception>
#include <cmath>
#include <cstdio>

#include "engine/method.hpp"
#include "generators/camera_paths.hpp"
#include "generators/city.hpp"
#include "generators/open_space.hpp"
#include "generators/roof_cameras.hpp"
#include "generators/random.hpp"
#include "oracle/oracle.hpp"
#include "reports/scene_source.hpp"
#include "reports/verification.hpp"

namespace cullcheck {

nlohmann::json to_json(const ClaimCheck& c) {
  nlohmann::json j = {{"id", c.id},
                      {"source", c.source},
                      {"statement", c.statement},
                      {"method", c.method},
                      {"holds", c.holds},
                      {"frames_checked", c.frames_checked},
                      {"violations", c.violations},
                      {"search_seconds", c.search_seconds}};
  if (!c.holds) j["counterexample"] = {{"replay", c.counterexample_replay}, {"detail", c.counterexample_detail}};
  return j;
}

SceneSource seeded_street_city(std::uint64_t seed, int index, std::uint64_t tag, const StreetCityRanges& r) {
  generators::Random draw = generators::Random::stream(seed, tag, static_cast<std::uint64_t>(index));
  SceneSource s;
  s.generator = "manhattan";
  s.seed = seed * 1000 + static_cast<std::uint64_t>(index);
  s.parameters_json = nlohmann::json{{"blocks_x", draw.uniform_int(r.min_blocks, r.max_blocks)},
                                     {"blocks_y", draw.uniform_int(r.min_blocks, r.max_blocks)},
                                     {"buildings_per_block", draw.uniform_int(r.min_lots, r.max_lots)},
                                     {"block_size", draw.uniform_int(r.min_block, r.max_block)},
                                     {"street_width", draw.uniform_int(r.min_street, r.max_street)},
                                     {"thin_fraction", r.thin_fraction}}
                          .dump();
  return s;
}

namespace {

// Small cities with occluders on both sides of eye height: thin slabs (wide, shallow roofs,
// whose far wall is much nearer than their end corners), low buildings and kiosks below a
// pedestrian's eye, some towers.
SceneSource search_scene(std::uint64_t seed, int index) {
  SceneSource s;
  s.generator = index % 2 == 0 ? "manhattan" : "plaza";
  s.seed = seed;
  nlohmann::json p = {{"blocks_x", 3},         {"blocks_y", 3},        {"buildings_per_block", 4},
                      {"thin_fraction", 0.5},  {"min_height", 3.0},    {"max_height", 20.0},
                      {"tower_fraction", 0.05}, {"tower_min_height", 30.0}, {"tower_max_height", 60.0}};
  if (s.generator == "plaza") p.update({{"plaza_blocks_x", 1}, {"plaza_blocks_y", 1}, {"kiosk_count", 8}});
  s.parameters_json = p.dump();
  return s;
}

// Cameras above the rooftops looking down, where roofs lie below the eye: seeded, uniform over
// the scene's plan, between 1.1 and 2.5 times the tallest roof, pitched 20-80 degrees down.
std::vector<Camera> rooftop_cameras(const Scene& scene, std::uint64_t seed, int count) {
  generators::Random random = generators::Random::stream(seed, 0xC1A1);
  const Box3 box = scene.bounds();
  std::vector<Camera> cameras;
  for (int i = 0; i < count; ++i) {
    Camera c;
    c.position = {random.uniform_real(box.lo.x, box.hi.x), random.uniform_real(box.lo.y, box.hi.y),
                  box.hi.z * random.uniform_real(1.1, 2.5)};
    c.yaw = random.uniform_real(0.0, kTwoPi);
    c.pitch = -random.uniform_real(20.0, 80.0) * kPi / 180;
    c.hfov = kPi / 3;
    c.vfov = kPi / 4;
    cameras.push_back(c);
  }
  return cameras;
}

// Seeded roof-facing cameras (generators/roof_cameras.hpp) over randomly drawn buildings.
std::vector<Camera> near_roof_cameras(const Scene& scene, std::uint64_t seed, int count) {
  generators::Random random = generators::Random::stream(seed, 0xC1A2);
  const generators::OpenSpace open(scene);
  std::vector<Camera> cameras;
  for (int i = 0; i < count && !scene.buildings.empty(); ++i) {
    const auto last = static_cast<std::int64_t>(scene.buildings.size()) - 1;
    const Building& b = scene.buildings[static_cast<std::size_t>(random.uniform_int(0, last))];
    const double side = random.bernoulli(0.5) ? 1.0 : -1.0;
    const double gap = random.uniform_real(1.0, 15.0);
    cameras.push_back(generators::roof_facing_camera(open, b, side, gap, random.uniform_real(0.5, 10.0)));
  }
  return cameras;
}

// Street-level cameras: evenly spaced frames of a seeded street walk (eye 1.7 m, level).
std::vector<Camera> street_cameras(const Scene& scene, std::uint64_t seed, int count) {
  const CameraPath path = generators::make_camera_path("street_walk", scene, seed, {{"frames", 600}});
  std::vector<Camera> cameras;
  const std::size_t stride = std::max<std::size_t>(1, path.frames.size() / std::max(1, count));
  for (std::size_t f = 0; f < path.frames.size() && cameras.size() < static_cast<std::size_t>(count); f += stride)
    cameras.push_back(path.frames[f]);
  return cameras;
}

// Seeded tilts: pitch only, roll only, or both. A camera that is already pitched keeps its pitch.
void tilt(std::vector<Camera>& cameras, std::uint64_t seed) {
  generators::Random random = generators::Random::stream(seed, 0xC1A3);
  const double degree = kPi / 180;
  for (Camera& c : cameras) {
    const auto kind = random.uniform_int(0, 2);
    // One draw per statement: the operands of * are unsequenced, so two draws in one expression
    // could come out in either order on another compiler.
    const double pitch_sign = random.bernoulli(0.5) ? 1 : -1;
    const double pitch = pitch_sign * random.uniform_real(0.5, 15.0) * degree;
    const double roll_sign = random.bernoulli(0.5) ? 1 : -1;
    const double roll = roll_sign * random.uniform_real(0.5, 30.0) * degree;
    if (kind != 1 && c.pitch == 0.0) c.pitch = pitch;
    if (kind != 0 || c.pitch == 0.0) c.roll = roll;
  }
}

ClaimCheck claim(std::string id, std::string source, std::string statement, std::string method) {
  ClaimCheck c;
  c.id = std::move(id);
  c.source = std::move(source);
  c.statement = std::move(statement);
  c.method = std::move(method);
  return c;
}

}  // namespace

namespace {
unsigned search_threads(unsigned threads, int scenes) { return thread_count(threads, static_cast<std::size_t>(std::max(1, scenes))); }
}  // namespace

oracle::OracleOptions for_one_scene(oracle::OracleOptions options, unsigned threads, int scenes) {
  if (search_threads(threads, scenes) > 1) options.sampling.threads = 1;
  return options;
}

void search_scenes(int scenes, unsigned threads, const Shard& shard, const std::vector<ClaimCheck*>& claims, const std::string& stage,
                   const std::function<void(int index, std::vector<ClaimCheck>& partial)>& search) {
  if (scenes <= 0) return;
  std::vector<ClaimCheck> blank;
  for (const ClaimCheck* c : claims) {
    ClaimCheck b = *c;
    b.holds = true;
    b.frames_checked = b.violations = 0;
    b.counterexample_replay.clear(), b.counterexample_detail.clear();
    b.counterexample_scene = -1;
    blank.push_back(std::move(b));
  }
  std::vector<std::vector<ClaimCheck>> partials(static_cast<std::size_t>(scenes), blank);
  Progress progress(stage, shard.share(static_cast<std::size_t>(scenes)), "scenes");
  for_each_index(static_cast<std::size_t>(scenes), search_threads(threads, scenes), [&] {
    return [&](std::size_t i) {
      if (!shard.owns(i)) return;
      search(static_cast<int>(i), partials[i]);
      progress.advance();
    };
  });
  for (std::size_t scene = 0; scene < partials.size(); ++scene)
    for (std::size_t k = 0; k < claims.size(); ++k) {
      const std::vector<ClaimCheck>& partial = partials[scene];
      ClaimCheck& c = *claims[k];
      const ClaimCheck& p = partial[k];
      c.frames_checked += p.frames_checked;
      c.violations += p.violations;
      if (!p.holds && c.holds) {
        c.holds = false;
        c.counterexample_replay = p.counterexample_replay;
        c.counterexample_detail = p.counterexample_detail;
        c.counterexample_scene = static_cast<int>(scene);
      }
    }
}

std::vector<ClaimCheck> check_shadow_elevation_rule(const ClaimSearchOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  ClaimCheck published = claim("thesis-3.1.2-shadow-elevation-rule",
                       "Koldas thesis, ch. 3.1.2 (object-space OH)",
                       "A CVP's shadow may take as its elevation the smaller elevation of its two extreme-azimuth "
                       "vertices, and OH(OS) with it stays conservative (6 DoF, up to 360 degrees).",
                       "oh_os_thesis");
  ClaimCheck corrected = claim("cullcheck-shadow-elevation-far-chain",
                       "cullcheck correction of thesis ch. 3.1.2",
                       "Taking the shadow's elevation from the far chain when the roof is below the eye (and from the "
                       "tangent vertices otherwise) keeps OH(OS) conservative.",
                       "oh_os_conservative");
  oracle::OracleOptions oracle_options;
  oracle_options.sampling = options.sampling;
  MethodOptions method_options;
  search_scenes(options.scenes, options.threads, options.shard, {&published, &corrected}, "claims search: the shadow elevation rule",
                [&options, &method_options, oracle_options = for_one_scene(oracle_options, options.threads, options.scenes)](int index, std::vector<ClaimCheck>& partial) {
    ClaimCheck& published = partial[0];
    ClaimCheck& corrected = partial[1];
    const std::uint64_t seed = options.seed + static_cast<std::uint64_t>(index);
    const SceneSource source = search_scene(seed, index);
    const Scene scene = source.load();
    std::vector<Camera> cameras = rooftop_cameras(scene, seed, options.cameras_per_scene);
    for (const Camera& c : near_roof_cameras(scene, seed, 4 * options.cameras_per_scene)) cameras.push_back(c);
    // Half as many again from a fly-through, which also dips to street level.
    const CameraPath path = generators::make_camera_path("fly_through", scene, seed, {{"frames", 240}});
    const std::size_t stride = std::max<std::size_t>(1, 2 * path.frames.size() / std::max(2, options.cameras_per_scene));
    for (std::size_t f = 0; f < path.frames.size(); f += stride)
      cameras.push_back(path.frames[f]);
    auto thesis = make_method(published.method, scene, method_options);
    auto conservative = make_method(corrected.method, scene, method_options);
    const oracle::Oracle truth(scene);
    for (const Camera& camera : cameras) {
      const oracle::OracleAnswer answer = truth.visible_set(camera, oracle_options);
      for (auto [claim, method] : {std::pair{&published, thesis.get()}, std::pair{&corrected, conservative.get()}}) {
        ++claim->frames_checked;
        const std::vector<ObjectId> missed = missing_from(answer.visible, method->cull(camera).pvs);
        claim->violations += missed.size();
        if (missed.empty() || !claim->holds) continue;
        claim->holds = false;
        claim->counterexample_replay = replay_command(source, claim->method, camera);
        claim->counterexample_detail = "building " + std::to_string(missed.front()) + " seen by the oracle (" +
                                       answer.model + ") but culled" +
                                       (answer.sampling ? ": " + oracle::describe(answer.sampling->witnesses.at(missed.front())) : "");
      }
    }
    });
  const double seconds = seconds_since(start);
  published.search_seconds = corrected.search_seconds = seconds;
  return {published, corrected};
}

std::vector<ClaimCheck> check_image_space_pitch_roll(const ClaimSearchOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  ClaimCheck tilted = claim("downs-oh-is-pitch-roll", "Koldas thesis, ch. 3.1.1, Fig. 3.3 (Downs et al.'s OH)",
                            "OH(IS), the occlusion horizon built in the view plane (screen x, with the camera's full view "
                            "transform), stays conservative when the camera pitches or rolls. The thesis says it does not: "
                            "it is conservative for level cameras only (4 DoF), so a counterexample confirms Fig. 3.3.",
                            "oh_is");
  ClaimCheck level = claim("downs-oh-is-level-cameras", "Downs et al., as described in thesis ch. 3.1.1",
                           "OH(IS) is conservative for level cameras (4 DoF: x, y, z, yaw), street level and above the "
                           "rooftops: the same cameras as the pitch/roll search, with pitch and roll set to 0.",
                           "oh_is");
  oracle::OracleOptions oracle_options;
  oracle_options.sampling = options.sampling;
  search_scenes(options.scenes, options.threads, options.shard, {&tilted, &level}, "claims search: OH(IS) with pitch and roll",
                [&options, oracle_options = for_one_scene(oracle_options, options.threads, options.scenes)](int index, std::vector<ClaimCheck>& partial) {
    ClaimCheck& tilted = partial[0];
    ClaimCheck& level = partial[1];
    const std::uint64_t seed = options.seed + static_cast<std::uint64_t>(index);
    const SceneSource source = search_scene(seed, index);
    const Scene scene = source.load();
    std::vector<Camera> cameras = street_cameras(scene, seed, options.cameras_per_scene);
    for (const Camera& c : rooftop_cameras(scene, seed, options.cameras_per_scene)) cameras.push_back(c);
    tilt(cameras, seed);
    auto method = make_method(level.method, scene);
    const oracle::Oracle truth(scene);
    auto check = [&](ClaimCheck& claim, const Camera& camera) {
      ++claim.frames_checked;
      const oracle::OracleAnswer answer = truth.visible_set(camera, oracle_options);
      const std::vector<ObjectId> missed = missing_from(answer.visible, method->cull(camera).pvs);
      claim.violations += missed.size();
      if (missed.empty() || !claim.holds) return;
      claim.holds = false;
      claim.counterexample_replay = replay_command(source, claim.method, camera);
      char tilt_text[96];
      std::snprintf(tilt_text, sizeof tilt_text, "camera pitch %.2f deg, roll %.2f deg", camera.pitch * 180 / kPi,
                    camera.roll * 180 / kPi);
      claim.counterexample_detail = "building " + std::to_string(missed.front()) + " seen by the oracle (" + answer.model +
                                    ") but culled; " + tilt_text +
                                    (answer.sampling ? ": " + oracle::describe(answer.sampling->witnesses.at(missed.front())) : "");
    };
    for (Camera camera : cameras) {
      check(tilted, camera);
      camera.pitch = camera.roll = 0.0;
      check(level, camera);
    }
    });
  tilted.search_seconds = level.search_seconds = seconds_since(start);
  return {tilted, level};
}

}  // namespace cullcheck
