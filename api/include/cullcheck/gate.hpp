// cullcheck's C++ API for a user's own tests (README "The library"): hold a culling system's
// visible set for one camera to the oracle, from GoogleTest or any test framework.
//
//   #include <cullcheck/gate.hpp>
//   const cullcheck::Gate gate("city.glb");                    // or .json / .obj, or a Scene
//   const cullcheck::FrameVerdict v = gate.check_conservative(camera, my_culler.visible(camera));
//   EXPECT_TRUE(v.passed) << v.message;                        // the message carries the replay
//
// check_conservative fails when the oracle sees an object the visible set lacks (ray sampling,
// and a misdrawn pixel at the camera's resolution); check_approximate when more pixels than the
// budget are misdrawn. Every failure names the objects, the witness rays and one command,
// `cullcheck gate --scene ... --camera ... --visible ...`, that reproduces the verdict.
//
// CMake: find_package(cullcheck) then target_link_libraries(mytests cullcheck::oracle).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/camera.hpp"
#include "core/scene.hpp"
#include "oracle/sampling.hpp"
#include "oracle/witness_recheck.hpp"

namespace cullcheck {

struct GateOptions {
  oracle::SamplingOptions sampling;  // the ray oracle's density (its defaults are the CLI's)
  bool pixels = true;                // also compare id buffers at the camera's resolution
  // How the replay names the scene; default "--scene FILE" for a Gate built from a file.
  std::string scene_flags;
};

struct FrameVerdict {
  bool passed = true;
  std::vector<ObjectId> missed;     // visible (witnessed) but not in the visible set
  std::size_t witnessed = 0;        // objects the oracle saw
  // Witnesses of missed objects re-cast in double precision before they count, and those
  // dropped because they did not stand (oracle/witness_recheck.hpp); dropped ones are not missed.
  oracle::WitnessRecheckCounts witness_recheck;
  std::uint64_t misdrawn_pixels = 0;
  std::uint64_t largest_blob = 0;   // 4-connected misdrawn pixels
  std::string oracle_model;         // exact_2d or ray_sampling_3d
  std::string message;              // empty when passed; else what failed, the witnesses and the replay
  std::string replay;               // a cullcheck command that reproduces this verdict
  explicit operator bool() const { return passed; }
};

class Gate {
 public:
  // Reads a scene file: cullcheck scene JSON, glTF 2.0 (.glb/.gltf, one object per node) or OBJ.
  // Throws cullcheck::InputError naming the file and field when it cannot be used.
  explicit Gate(const std::string& scene_file, GateOptions options = {});
  Gate(Scene scene, GateOptions options = {});
  ~Gate();
  Gate(Gate&&) noexcept;
  Gate& operator=(Gate&&) noexcept;

  // `visible`: the ids the culling system did not cull, in any order.
  FrameVerdict check_conservative(const Camera& camera, std::vector<ObjectId> visible) const;
  FrameVerdict check_approximate(const Camera& camera, std::vector<ObjectId> visible, std::uint64_t pixel_budget) const;
  // What the oracle sees from `camera` (witnessed ids, sorted).
  std::vector<ObjectId> visible_set(const Camera& camera) const;
  const Scene& scene() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace cullcheck
