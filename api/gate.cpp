#include "cullcheck/gate.hpp"

#include <algorithm>
#include <iterator>

#include "core/replay_text.hpp"
#include "core/scene_io.hpp"
#include "core/formats/mesh_formats.hpp"
#include "oracle/oracle.hpp"

namespace cullcheck {
struct Gate::Impl {
  Scene scene;
  GateOptions options;
  std::unique_ptr<oracle::Oracle> truth;
  Impl(Scene s, GateOptions o) : scene(std::move(s)), options(std::move(o)), truth(std::make_unique<oracle::Oracle>(scene)) {}

  FrameVerdict check(const Camera& camera, std::vector<ObjectId> visible, const std::uint64_t* budget) const {
    std::sort(visible.begin(), visible.end());
    visible.erase(std::unique(visible.begin(), visible.end()), visible.end());
    FrameVerdict v;
    oracle::OracleOptions oo;
    oo.sampling = options.sampling;
    oracle::OracleAnswer answer = truth->visible_set(camera, oo);
    v.oracle_model = answer.model;
    v.witnessed = answer.visible.size();
    std::set_difference(answer.visible.begin(), answer.visible.end(), visible.begin(), visible.end(), std::back_inserter(v.missed));
    // A witness counts only if it stands re-cast in double precision (Embree casts in floats).
    if (answer.sampling)
      std::erase_if(v.missed, [&](ObjectId id) { return !truth->confirm_witness(answer, id, camera).stands(); });
    std::string witnesses;
    for (ObjectId id : v.missed)
      if (answer.sampling && answer.sampling->witnesses.count(id))
        witnesses += "\n  object " + std::to_string(id) + ": " + oracle::describe(answer.sampling->witnesses.at(id));
    if (options.pixels || budget) {
      const oracle::PixelComparison pixels = truth->pixels().compare(camera, visible, options.sampling.threads);
      v.misdrawn_pixels = pixels.misdrawn_pixels;
      v.largest_blob = pixels.largest_blob;
      for (const auto& [id, ray] : pixels.witnesses) {
        if (std::binary_search(v.missed.begin(), v.missed.end(), id)) continue;
        if (!truth->recheck_witness(answer, id, ray, camera).stands()) continue;
        v.missed.insert(std::upper_bound(v.missed.begin(), v.missed.end(), id), id);
        witnesses += "\n  object " + std::to_string(id) + ": " + oracle::describe(ray);
      }
    }
    v.witness_recheck = answer.witness_recheck;
    v.replay = "cullcheck gate " + options.scene_flags + " --camera " + camera_arg(camera) + " --visible " + shell_quote(ids_text(visible)) +
               (budget ? " --claims approximate --pixel-budget " + std::to_string(*budget) : "");
    if (budget) {
      v.passed = v.misdrawn_pixels <= *budget;
      if (!v.passed)
        v.message = std::to_string(v.misdrawn_pixels) + " misdrawn pixels, above the budget of " + std::to_string(*budget) +
                    " (largest blob " + std::to_string(v.largest_blob) + ")" + witnesses;
    } else {
      v.passed = v.missed.empty();
      if (!v.passed)
        v.message = "culled " + std::to_string(v.missed.size()) + " object(s) the oracle sees (" + answer.model + ", " +
                    std::to_string(v.misdrawn_pixels) + " misdrawn pixels):" + witnesses;
    }
    if (!v.passed) v.message += "\nreplay: " + v.replay;
    return v;
  }
};

Gate::Gate(const std::string& scene_file, GateOptions options) {
  if (options.scene_flags.empty()) options.scene_flags = "--scene " + shell_quote(scene_file);
  impl_ = std::make_unique<Impl>(formats::read_scene_file_any(scene_file), std::move(options));
}
Gate::Gate(Scene scene, GateOptions options) {
  if (options.scene_flags.empty()) options.scene_flags = "--scene SCENE.json";
  impl_ = std::make_unique<Impl>(std::move(scene), std::move(options));
}
Gate::~Gate() = default;
Gate::Gate(Gate&&) noexcept = default;
Gate& Gate::operator=(Gate&&) noexcept = default;

FrameVerdict Gate::check_conservative(const Camera& camera, std::vector<ObjectId> visible) const {
  return impl_->check(camera, std::move(visible), nullptr);
}
FrameVerdict Gate::check_approximate(const Camera& camera, std::vector<ObjectId> visible, std::uint64_t pixel_budget) const {
  return impl_->check(camera, std::move(visible), &pixel_budget);
}
std::vector<ObjectId> Gate::visible_set(const Camera& camera) const {
  oracle::OracleOptions oo;
  oo.sampling = impl_->options.sampling;
  return impl_->truth->visible_set(camera, oo).visible;
}
const Scene& Gate::scene() const { return impl_->scene; }

}  // namespace cullcheck
