#include "reports/verification.hpp"

#include "core/elapsed.hpp"
#include "core/errors.hpp"
#include "core/scene_timeline.hpp"
#include "core/progress.hpp"

#include "engine/shrinking/circle_tiling.hpp"
#include "engine/spatial/traversal_bound.hpp"

#include <algorithm>
#include <set>
#include <chrono>
#include <cmath>
#include <iterator>
#include <memory>
#include <optional>

#include "core/scene_io.hpp"
#include "reports/held_conservative.hpp"
#include "reports/test_costs.hpp"
#include "subjects/subject_error.hpp"

namespace cullcheck {

std::vector<ObjectId> missing_from(const std::vector<ObjectId>& visible, const std::vector<ObjectId>& pvs) {
  std::vector<ObjectId> missing;
  std::set_difference(visible.begin(), visible.end(), pvs.begin(), pvs.end(), std::back_inserter(missing));
  return missing;
}

std::string replay_command(const SceneSource& source, const std::string& method, const Camera& camera) {
  return "cullcheck verify " + source.replay_flags() + " --method " + method + " --camera " + camera_arg(camera);
}

std::string region_replay_command(const SceneSource& source, const std::string& method, const Camera& centre,
                                  double radius, double turn, const Camera& viewpoint) {
  return "cullcheck region " + source.replay_flags() + " --method " + method + " --camera " + camera_arg(centre) + " --radius " +
         round_trip_text(radius) + " --turn " + round_trip_text(turn) + " --from " + camera_arg(viewpoint);
}

namespace {

// Whether a camera is one of the region's: eye within the disc at its height, turned no more
// than the region allows, same fields of view and clip planes.
bool region_holds(const ViewRegion& region, const Camera& c) {
  const Camera& a = region.camera;
  if (c.hfov != a.hfov || c.vfov != a.vfov || c.near != a.near || c.far != a.far || c.position.z != a.position.z) return false;
  if (length(plan(c.position) - plan(a.position)) > region.radius) return false;
  if (a.omnidirectional()) return true;
  return std::abs(std::remainder(c.yaw - a.yaw, kTwoPi)) + std::abs(c.pitch - a.pitch) + std::abs(c.roll - a.roll) <= region.turn;
}

// An object the oracle saw at `frame` and a method culled, with its witness: the oracle's when
// it saw the object, else (`pixels`, model "pixel_ids") the pixel ray that showed it.
Violation violation_of(std::size_t frame, ObjectId building, const Camera& camera, const oracle::OracleAnswer& answer,
                       std::string replay, const oracle::PixelComparison* pixels = nullptr) {
  Violation v;
  v.frame = frame;
  v.building = building;
  v.camera = camera;
  v.replay = std::move(replay);
  // The pixel's witness when the ray oracle has none for it, or has one that did not stand.
  const auto verdict = answer.rechecked.find({building, false});
  const bool ray_stands = verdict == answer.rechecked.end() || verdict->second.stands();
  if ((!std::binary_search(answer.visible.begin(), answer.visible.end(), building) || !ray_stands) && pixels &&
      pixels->witnesses.count(building)) {
    v.model = "pixel_ids";
    v.witness = oracle::describe(pixels->witnesses.at(building));
    return v;
  }
  v.model = answer.model;
  if (answer.sampling) v.witness = oracle::describe(answer.sampling->witnesses.at(building));
  return v;
}

// A missed object counts only when its witness ray stands re-cast in double precision (the
// oracle casts in single precision: oracle/witness_recheck.hpp): the ray oracle's witness when
// it saw the object (or a further witness of it that stands), else the pixel oracle's. The
// others are dropped here, and both are counted for the method. The exact 2D model has no ray
// to doubt.
void drop_unconfirmed(const oracle::Oracle& truth, oracle::OracleAnswer& answer, const Camera& camera,
                      const oracle::PixelComparison* pixels, std::vector<ObjectId>& missed, oracle::WitnessRecheckCounts& counts) {
  std::erase_if(missed, [&](ObjectId id) {
    const bool sampled = std::binary_search(answer.visible.begin(), answer.visible.end(), id);
    if (sampled && !answer.sampling) return false;
    const oracle::WitnessRay* pixel = nullptr;
    if (pixels)
      if (const auto found = pixels->witnesses.find(id); found != pixels->witnesses.end()) pixel = &found->second;
    if (!sampled && !pixel) return false;
    // The ray oracle's witnesses first; the pixel's when those do not stand (or there are none).
    bool stands = sampled && truth.confirm_witness(answer, id, camera).stands();
    if (!stands && pixel) stands = truth.recheck_witness(answer, id, *pixel, camera).stands();
    ++counts.checked;
    counts.dropped += stands ? 0 : 1;
    return !stands;
  });
}

// Keeps this checked frame as the run's snapshot when it is the frame asked for, or (none asked
// for) when it is worse than the one kept. The copies are made only then.
void keep_snapshot(MethodRun& run, std::size_t index, const Camera& camera, const std::vector<ObjectId>& pvs,
                   const oracle::OracleAnswer& answer, const oracle::PixelComparison* pixel, const std::vector<ObjectId>& missed,
                   const std::optional<std::size_t>& wanted) {
  std::size_t seen_in_pvs = 0;
  for (ObjectId id : answer.visible) seen_in_pvs += std::binary_search(pvs.begin(), pvs.end(), id) ? 1 : 0;
  FrameSnapshot s;
  s.frame = index;
  s.overestimate = pvs.size() - seen_in_pvs;
  s.missed = missed;
  if (wanted ? *wanted != index : run.snapshot && !worse_frame(s, *run.snapshot)) return;
  s.camera = camera;
  s.pvs = pvs;
  s.seen = answer.visible;
  if (pixel)
    for (const auto& [id, ray] : pixel->witnesses) s.seen.push_back(id);
  std::sort(s.seen.begin(), s.seen.end());
  s.seen.erase(std::unique(s.seen.begin(), s.seen.end()), s.seen.end());
  for (ObjectId id : missed) {
    if (answer.sampling && answer.sampling->witnesses.count(id)) s.witness_rays.push_back(answer.sampling->witnesses.at(id));
    else if (pixel && pixel->witnesses.count(id)) s.witness_rays.push_back(pixel->witnesses.at(id));
  }
  run.snapshot = std::move(s);
}

}  // namespace

void settle_violations(MethodRun& run) {
  run.claims_conservative = run.claims_every_camera || run.frames_claimed > 0;
  const ViolationTally& tally = run.claims_conservative ? run.claimed_frames : run.every_frame;
  run.violation_count = tally.count;
  run.frames_with_violations = tally.frames;
  run.violations = tally.kept;
}

bool worse_frame(const FrameSnapshot& a, const FrameSnapshot& b) {
  if (a.missed.size() != b.missed.size()) return a.missed.size() > b.missed.size();
  return a.overestimate > b.overestimate;
}

// The gate (report.cpp's conservative_violations) counts the violations of the runs whose
// claims_conservative is set. A method's claim may depend on the camera (claims_conservative_for:
// OH(IS) claims level cameras only), so a run is held to the gate when its method claims
// conservativeness for every camera or for at least one checked frame, and then its violations
// are those of the frames its claim covers; a run whose method claims no checked frame keeps
// every violation, reported but not gated (e.g. oh_os_thesis, or oh_is along a fly-through).
// For methods whose claim does not depend on the camera this is the plain count either way.
std::vector<MethodUnderTest> builtin_methods(const Scene& scene, const SceneSource& source, const std::vector<std::string>& names,
                                             const MethodOptions& method_options, const VerificationOptions& options,
                                             std::vector<std::pair<std::string, std::string>>* skipped) {
  std::vector<MethodUnderTest> out;
  const std::string held = options.hold_conservative ? " --hold-conservative" : "";
  for (const std::string& name : names) {
    if (const std::string why = method_unavailable_reason(name, scene); !why.empty()) {
      if (skipped) skipped->emplace_back(name, why);
      continue;
    }
    MethodUnderTest m;
    m.method = make_method(name, scene, method_options);
    if (options.hold_conservative) m.method = held_conservative(std::move(m.method));
    const bool incremental = m.method->incremental() && !options.path_replay_flags.empty();
    m.replay = [source, name, incremental, held, path_flags = options.path_replay_flags](std::size_t frame, const Camera& camera) {
      if (incremental)
        return "cullcheck verify " + source.replay_flags() + " " + path_flags + " --method " + name + held + "   # violation at frame " +
               std::to_string(frame);
      return replay_command(source, name, camera) + held;
    };
    out.push_back(std::move(m));
  }
  return out;
}

PathVerification verify_path(const Scene& scene, const SceneSource& source, const CameraPath& path,
                             const std::vector<std::string>& methods, const MethodOptions& method_options,
                             const VerificationOptions& options) {
  std::vector<std::pair<std::string, std::string>> skipped;
  std::vector<MethodUnderTest> engines = builtin_methods(scene, source, methods, method_options, options, &skipped);
  PathVerification out = verify_path(scene, source, path, engines, method_options, options);
  // Point methods first, then the region methods verify_path skipped itself.
  out.skipped_methods.insert(out.skipped_methods.begin(), skipped.begin(), skipped.end());
  return out;
}

PathVerification verify_path(const Scene& scene, const SceneSource& source, const CameraPath& path,
                             std::vector<MethodUnderTest>& engines, const MethodOptions& method_options,
                             const VerificationOptions& options) {
  PathVerification out;
  const std::size_t n = engines.size();
  out.oracle.density = options.oracle.sampling;
  out.oracle.oracle_stride = std::max<std::size_t>(1, options.oracle_stride);
  std::vector<std::size_t> builtin;  // runs an outside subject's PVS is compared with
  for (std::size_t m = 0; m < n; ++m) {
    MethodRun run;
    run.method = engines[m].method->name();
    run.claims_conservative = run.claims_every_camera = engines[m].method->claims_conservative();
    run.outside = engines[m].outside;
    run.pixel_error_budget = engines[m].method->pixel_error_budget();
    if (!run.outside) builtin.push_back(m);
    out.runs.push_back(std::move(run));
  }
  for (std::size_t m = 0; m < n; ++m)
    if (out.runs[m].outside)
      for (std::size_t b : builtin) out.runs[m].frames_equal_to.emplace_back(out.runs[b].method, 0);
  std::vector<std::unique_ptr<RegionCullingMethod>> region_engines;
  std::vector<std::optional<ViewRegion>> current(options.region_methods.size());
  std::vector<std::vector<ObjectId>> region_pvs(options.region_methods.size());
  for (const std::string& name : options.region_methods) {
    if (const std::string why = method_unavailable_reason(name, scene); !why.empty()) {
      out.skipped_methods.emplace_back(name, why);
      continue;
    }
    region_engines.push_back(make_region_method(name, scene, method_options));
    RegionRun run;
    run.method = name;
    run.claims_conservative = region_engines.back()->claims_conservative();
    run.radius = options.region_radius;
    run.turn = options.region_turn;
    run.on_tiling = options.region_on_tiling;
    out.regions.push_back(std::move(run));
  }
  std::size_t reference = n;
  for (std::size_t m = 0; m < n; ++m)
    if (out.runs[m].method == options.reference_method) reference = m;
  // The scene timeline (core/scene_timeline.hpp): the scenes of the present objects, kept while
  // a rebuilt method or the oracle refers to them.
  PresentScenes present_scenes(scene);
  std::unique_ptr<oracle::Oracle> oracle_now = std::make_unique<oracle::Oracle>(scene);
  const oracle::Oracle* truth = oracle_now.get();
  const Scene* scene_now = &scene;  // the scene the built-in methods were built on
  std::vector<std::unique_ptr<ExactTraversal>> traversals(n);  // per method that sweeps a quadtree
  const auto change_scene = [&](const std::vector<ObjectId>& appeared, const std::vector<ObjectId>& vanished) {
    const Scene& present = present_scenes.apply(appeared, vanished);
    scene_now = &present;
    for (auto& t : traversals) t.reset();
    for (std::size_t m = 0; m < n; ++m) {
      if (engines[m].method->update_scene(present, appeared, vanished)) continue;
      if (engines[m].outside)
        throw InputError("path", "events", out.runs[m].method + " cannot follow a scene timeline: the subject protocol has no scene changes yet");
      engines[m].method = make_method(out.runs[m].method, present, method_options);
      if (options.hold_conservative) engines[m].method = held_conservative(std::move(engines[m].method));
    }
    for (std::size_t r = 0; r < region_engines.size(); ++r) {
      region_engines[r] = make_region_method(out.regions[r].method, present, method_options);
      current[r].reset();
    }
    oracle_now = std::make_unique<oracle::Oracle>(present);
    truth = oracle_now.get();
  };
  std::size_t next_event = 0;
  if (!path.events.empty()) {
    validate_timeline(path, scene, options.first_frame + path.frames.size());
    // The state at the first frame given: the objects absent from the start, then every event up to it.
    std::set<ObjectId> start = absent_at_start(path);
    for (; next_event < path.events.size() && path.events[next_event].frame <= options.first_frame; ++next_event) {
      for (ObjectId id : path.events[next_event].vanish) start.insert(id);
      for (ObjectId id : path.events[next_event].appear) start.erase(id);
    }
    if (!start.empty()) change_scene({}, std::vector<ObjectId>(start.begin(), start.end()));
  }
  oracle::RayLog first_log;
  bool pixels = options.pixels;
  for (const MethodRun& run : out.runs) pixels = pixels || run.pixel_error_budget.has_value();
  out.pixels.enabled = pixels;
  const double frame_seconds = path.frames_per_second > 0 ? 1.0 / path.frames_per_second : 0.0;
  Progress progress("methods and the oracle along the path", path.frames.size(), "frames");
  for (std::size_t frame = 0; frame < path.frames.size(); ++frame) {
    const Camera& camera = path.frames[frame];
    const std::size_t index = options.first_frame + frame;  // the frame's number along the original path
    if (next_event < path.events.size() && path.events[next_event].frame == index) {
      change_scene(path.events[next_event].appear, path.events[next_event].vanish);
      ++next_event;
    }
    // Every method answers before anything is recorded, so a subject failing at this frame
    // leaves every run with the same frames.
    std::vector<std::optional<CullResult>> results(n);
    std::vector<std::string> unsupported(n);
    std::size_t m = 0;
    try {
      for (; m < n; ++m) {
        unsupported[m] = engines[m].method->unsupported_camera(camera);
        if (!unsupported[m].empty()) continue;
        engines[m].method->set_frame(index, static_cast<double>(index) * frame_seconds);
        results[m] = engines[m].method->cull(camera);
        // Outside the method's own timing: what an exact traversal of its quadtree would test.
        take_exact_traversal(*engines[m].method, *scene_now, traversals[m], *results[m]);
      }
    } catch (const SubjectError& e) {
      out.aborted = Abort{out.runs[m].method, e.frame(), SubjectError::kind_name(e.kind()), e.what()};
      break;
    }
    out.frames_run = frame + 1;
    progress.advance();
    for (m = 0; m < n; ++m) {
      MethodRun& run = out.runs[m];
      if (!results[m]) {
        if (run.frames_skipped++ == 0) run.skip_reason = unsupported[m];
        continue;
      }
      const CullStatistics& s = results[m]->stats;
      run.cull_ms.push_back(s.cull_ms);
      run.answered_frames.push_back(index);
      run.protocol_ms.push_back(s.protocol_ms);
      run.background_ms.push_back(s.background_ms);
      run.pvs_size.push_back(static_cast<double>(results[m]->pvs.size()));
      add_counts(run.totals, s);
      if (run.outside)
        for (std::size_t k = 0; k < builtin.size(); ++k)
          if (results[builtin[k]] && results[builtin[k]]->pvs == results[m]->pvs) ++run.frames_equal_to[k].second;
    }
    const bool reference_answered = reference < n && results[reference].has_value();
    for (std::size_t m = 0; m < region_engines.size(); ++m) {
      RegionRun& run = out.regions[m];
      if (camera.orthographic()) continue;  // a disc of eyes needs an eye point
      if (!current[m] || !region_holds(*current[m], camera)) {
        current[m] = ViewRegion{camera, options.region_radius, options.region_turn};
        if (options.region_on_tiling) {
          const Vec2 c = CircleTiling{options.region_radius}.nearest_centre(plan(camera.position));
          current[m]->camera.position = {c.x, c.y, camera.position.z};
        }
        const CullResult r = region_engines[m]->cull_region(*current[m]);
        region_pvs[m] = r.pvs;
        run.compute_ms.push_back(r.stats.cull_ms);
      }
      run.pvs_size.push_back(static_cast<double>(region_pvs[m].size()));
      if (reference_answered) run.point_pvs_size.push_back(static_cast<double>(results[reference]->pvs.size()));
    }
    if (reference_answered)
      for (std::size_t m = 0; m < n; ++m) {
        if (!results[m]) continue;
        out.runs[m].compared_with_reference = true;
        out.runs[m].frames_differing_from_reference += results[m]->pvs != results[reference]->pvs ? 1 : 0;
      }
    if (frame % out.oracle.oracle_stride != 0 || !options.shard.owns(frame / out.oracle.oracle_stride)) continue;
    // The first ray-sampling frame's rays are logged, to time them again in a bare Embree loop.
    oracle::OracleAnswer answer = truth->visible_set(camera, options.oracle, options.measure_bare_embree && first_log.rays.empty() ? &first_log : nullptr);
    ++out.oracle.frames_checked;
    out.checked_frames.push_back(index);
    out.checked_visible.push_back(answer.visible);
    out.oracle.seconds += answer.elapsed_seconds;
    if (answer.sampling) {
      ++out.oracle.frames_ray_sampling;
      out.oracle.rays_cast += answer.sampling->rays_cast;
      out.oracle.grazing_rays += answer.sampling->grazing_rays;
      out.oracle.rays_skipped += answer.sampling->rays_skipped;
      out.oracle.sampling_seconds += answer.sampling->elapsed_seconds;
    } else {
      ++out.oracle.frames_exact_2d;
    }
    // The pixel oracle: one full id buffer per checked frame, compared with every PVS.
    std::optional<oracle::IdImage> full;
    if (pixels) {
      const auto pixel_start = std::chrono::steady_clock::now();
      full = truth->pixels().render(camera, nullptr, options.oracle.sampling.threads);
      ++out.pixels.frames;
      out.pixels.rays += full->ids.size();
      out.pixels.seconds += seconds_since(pixel_start);
    }
    for (std::size_t m = 0; m < n; ++m) {
      if (!results[m]) continue;
      MethodRun& run = out.runs[m];
      const std::vector<ObjectId>& pvs = results[m]->pvs;
      run.checked_pvs_size.push_back(static_cast<double>(pvs.size()));
      run.witnessed_size.push_back(static_cast<double>(answer.visible.size()));
      const bool claimed = engines[m].method->claims_conservative_for(camera);
      run.frames_claimed += claimed ? 1 : 0;
      std::vector<ObjectId> missed = missing_from(answer.visible, pvs);
      std::optional<oracle::PixelComparison> pixel;
      if (full) {
        const auto pixel_start = std::chrono::steady_clock::now();
        pixel = truth->pixels().compare(*full, camera, pvs, options.oracle.sampling.threads);
        out.pixels.rays += pixel->misdrawn_pixels;
        out.pixels.seconds += seconds_since(pixel_start);
        run.misdrawn_pixels.push_back(static_cast<double>(pixel->misdrawn_pixels));
        run.blob_per_frame.push_back(pixel->largest_blob);
        run.pixel_frames.push_back(index);
        run.misdrawn_total += pixel->misdrawn_pixels;
        run.error_frames += pixel->misdrawn_pixels > 0 ? 1 : 0;
        run.largest_blob = std::max(run.largest_blob, pixel->largest_blob);
        run.most_misdrawn = std::max(run.most_misdrawn, pixel->misdrawn_pixels);
        if (run.pixel_error_budget && pixel->misdrawn_pixels > *run.pixel_error_budget) {
          ++run.frames_over_budget;
          if (run.over_budget.size() < options.max_replays) {
            ObjectId worst = 0;
            std::uint64_t most = 0;
            for (const auto& [id, count] : pixel->misdrawn_by_object)
              if (count > most) worst = id, most = count;
            Violation x;
            x.frame = index;
            x.building = worst;
            x.camera = camera;
            x.model = "pixel_ids";
            x.witness = std::to_string(pixel->misdrawn_pixels) + " misdrawn pixels (budget " + std::to_string(*run.pixel_error_budget) +
                        "), largest blob " + std::to_string(pixel->largest_blob) + ", most of them object " + std::to_string(worst);
            x.replay = engines[m].replay(index, camera);
            run.over_budget.push_back(std::move(x));
          }
        }
        // Every misdrawn pixel shows an object the PVS culled: a witness the ray sampling may not have.
        for (const auto& [id, ray] : pixel->witnesses)
          if (!std::binary_search(answer.visible.begin(), answer.visible.end(), id)) missed.push_back(id);
        std::sort(missed.begin(), missed.end());
      }
      drop_unconfirmed(*truth, answer, camera, pixel ? &*pixel : nullptr, missed, run.witness_recheck);
      run.checked_frames.push_back(index);
      keep_snapshot(run, index, camera, pvs, answer, pixel ? &*pixel : nullptr, missed, options.snapshot_frame);
      if (missed.empty()) continue;
      for (ViolationTally* tally : {&run.every_frame, claimed ? &run.claimed_frames : nullptr}) {
        if (tally == nullptr) continue;
        tally->count += missed.size();
        ++tally->frames;
        for (ObjectId id : missed) {
          if (tally->kept.size() >= options.max_replays) break;
          tally->kept.push_back(violation_of(index, id, camera, answer, engines[m].replay(index, camera), pixel ? &*pixel : nullptr));
        }
      }
    }
    // A disc of eyes needs an eye point: no region runs for an orthographic camera.
    for (std::size_t m = 0; !camera.orthographic() && m < region_engines.size(); ++m) {
      RegionRun& run = out.regions[m];
      run.checked_pvs_size.push_back(static_cast<double>(region_pvs[m].size()));
      run.witnessed_size.push_back(static_cast<double>(answer.visible.size()));
      run.checked_frames.push_back(index);
      std::vector<ObjectId> missed = missing_from(answer.visible, region_pvs[m]);
      drop_unconfirmed(*truth, answer, camera, nullptr, missed, run.witness_recheck);
      if (missed.empty()) continue;
      run.violation_count += missed.size();
      ++run.frames_with_violations;
      for (ObjectId id : missed) {
        if (run.violations.size() >= options.max_replays) break;
        run.violations.push_back(violation_of(
            index, id, camera, answer, region_replay_command(source, run.method, current[m]->camera, run.radius, run.turn, camera)));
      }
    }
    out.oracle.witness_recheck += answer.witness_recheck;
  }
  for (MethodRun& run : out.runs) settle_violations(run);
  if (options.measure_bare_embree && !first_log.rays.empty()) {
    out.oracle.bare_embree_rays_per_second = truth->rays().bare_embree_rays_per_second(first_log, options.oracle.sampling.threads);
    out.oracle.bare_embree_packet_rays_per_second =
        truth->rays().bare_embree_rays_per_second(first_log, options.oracle.sampling.threads, 0.2, /*packets=*/true);
  }
  return out;
}

}  // namespace cullcheck
