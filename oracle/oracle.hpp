// The oracle's one entry point (design: "Oracle"): what is really visible from a camera.
//
// It picks the cheapest model that is exact for the scene and camera, and says which:
//  - "exact_2d": plan-view visibility with exact CGAL geometry, when check_exact_2d says the
//    plan view is the 3D truth (level camera, every building taller than the eye, nothing can
//    be seen over a building, far beyond the scene). `visible` is then the true visible set.
//  - "ray_sampling_3d": Embree ray sampling otherwise. `visible` is the witnessed set, a lower
//    bound of the true visible set at the stated sampling density; every member has a
//    witness ray.
// Pixel truth (pixels()): the id buffers of the full scene and of a PVS at the camera's
// resolution, and the misdrawn pixels between them (pixel_oracle.hpp), on the same Embree scene.
// Witness re-check (recheck_witness): before a ray or pixel witness makes a violation, it is
// re-cast in double precision against the oracle's triangles (witness_recheck.hpp); a witness
// that does not stand there is dropped, and the answer counts both.
#pragma once

#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "oracle/exact_2d.hpp"
#include "oracle/pixel_oracle.hpp"
#include "oracle/ray_oracle.hpp"
#include "oracle/witness_recheck.hpp"

namespace cullcheck::oracle {

inline constexpr const char* kModelExact2d = "exact_2d";
inline constexpr const char* kModelRaySampling3d = "ray_sampling_3d";

struct OracleOptions {
  SamplingOptions sampling;
  bool allow_exact_2d = true;  // false forces ray sampling (e.g. to compare the two models)
};

struct OracleAnswer {
  std::string model;             // kModelExact2d or kModelRaySampling3d
  std::string why;               // why this model was picked (check_exact_2d's reason)
  bool exact = false;            // true when `visible` is the true visible set
  std::vector<ObjectId> visible;  // sorted ids
  std::optional<Exact2dResult> exact_2d;  // set when model == exact_2d
  std::optional<OracleResult> sampling;   // set when model == ray_sampling_3d
  double elapsed_seconds = 0.0;
  // Witnesses re-checked in double precision for this answer (Oracle::recheck_witness) and how
  // many were dropped; the verdicts by (object, whether the witness is a pixel's), so that each
  // is re-cast once however many methods culled the object.
  WitnessRecheckCounts witness_recheck;
  std::map<std::pair<ObjectId, bool>, WitnessRecheck> rechecked;
};

class Oracle {
 public:
  // Builds the Embree scene now; the exact 2D structure on the first query that needs it.
  // The Scene must outlive the oracle.
  explicit Oracle(const Scene& scene);
  ~Oracle();

  // With `log`, the rays of a ray-sampling query are appended to it (see RayOracle::witness).
  OracleAnswer visible_set(const Camera& camera, const OracleOptions& options = {}, RayLog* log = nullptr) const;

  // Whether the ray-sampling witness of `object` (answer.sampling->witnesses) stands when re-cast
  // in double precision for `camera`. When the first witness does not, its further witnesses are
  // tried in ray order and the first that stands replaces it in answer.sampling->witnesses (so a
  // violation's replay prints a ray that holds). Re-checked once per object and answer: the
  // verdict is kept in answer.rechecked and counted in answer.witness_recheck (one witness
  // checked; dropped when none of its rays stands). Throws std::logic_error if the answer has no
  // ray-sampling witness of `object`.
  const WitnessRecheck& confirm_witness(OracleAnswer& answer, ObjectId object, const Camera& camera) const;
  // The same for one given witness ray of `object` (e.g. a pixel oracle's witness, kept apart from
  // the ray-sampling ones by its RaySource::pixel).
  const WitnessRecheck& recheck_witness(OracleAnswer& answer, ObjectId object, const WitnessRay& ray,
                                        const Camera& camera) const;

  const RayOracle& rays() const { return rays_; }
  const PixelOracle& pixels() const { return pixels_; }
  const ExactVisibility2d& exact_2d() const;
  const DoublePrecisionScene& exact_triangles() const { return triangles_; }

 private:
  const Scene& scene_;
  RayOracle rays_;
  PixelOracle pixels_{rays_};  // after rays_, whose Embree scene it shares
  DoublePrecisionScene triangles_{rays_.mesh()};  // the same triangles, in double precision
  mutable std::once_flag exact_once_;
  mutable std::unique_ptr<ExactVisibility2d> exact_;
};

}  // namespace cullcheck::oracle
