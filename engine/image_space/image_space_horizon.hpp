// Image-space occlusion horizon culling, OH(IS): Downs et al.'s method as the thesis describes
// it in ch. 3.1.1 (Fig. 3.1-3.3). A baseline for OH(OS) (engine/horizon/), which moved the
// horizon to polar coordinates to get rid of this method's limit.
//
// Claim: conservative for 4 DoF only (x, y, z, yaw): claims_conservative_for(camera) is true for
// level cameras (pitch == 0 and roll == 0) and false otherwise, so claims_conservative() (every
// camera) is false. When the camera pitches or rolls, the horizon cannot be built conservatively
// in the view plane (Fig. 3.3); this class does what a direct port does anyway (projects with
// the full view transform, pitch and roll included), and the claims ledger and
// properties/image_space_horizon_test.cpp show the failure. Omnidirectional cameras
// (hfov >= 2*pi) have no view plane: for them OH(IS) is plain view-volume culling (no occlusion
// at all), which is conservative, so the claim covers them too.
//
// The view plane is the plane at unit distance along the view direction: a point p seen from
// the eye e has depth = forward·(p−e), screen x = right·(p−e) / depth and screen y =
// up·(p−e) / depth (basis_of: yaw, pitch and roll — what gluProject computes with the camera's
// view matrix, up to the focal length, which is 1 here: screen coordinates are tangents). The
// screen spans x ∈ [−tan(hfov/2), +tan(hfov/2)].
//
// Per query: the horizon H(x) starts at −inf over the screen and +inf beside it; the quadtree is
// swept front to back by plan distance, as in OH(OS); a cell or building is culled when it lies
// outside the view volume, or when every corner of its box lies deeper than the near plane and
// the highest projected corner is below min H over the bins its projected x range touches. A
// building whose box survives is in the PVS unless each of its CVPs is hidden the same way. The
// CVPs of a building in the PVS become shadows: x range [xmin, xmax] over the projections of the
// prism's corners, height the smaller projected top y of the two extreme-x vertices (the
// published rule). A shadow is merged into H only once the sweep has passed the CVP's farthest
// point ("update OH at its maximum distance"); a CVP with a vertex in front of the near plane
// (depth < near) is not used: its clipped part hides nothing.
//
// Why the published height is exact for a level camera: a convex prism in front of the eye
// projects to a convex polygon, whose upper boundary is a concave function of x, so its minimum
// over [xmin, xmax] lies at an end; with level cameras the screen column through x is a vertical
// plane through the eye, and the column at an end of the range meets the prism only in the
// vertical edge of the extreme vertex, whose top is the highest point there. A sight line below
// the upper boundary of that polygon stays at z >= 0 on its way to anything standing on the
// ground behind the CVP, so it passes through the prism. Neither step survives pitch or roll
// (columns are no longer vertical: a line of sight can pass under or beside the prism), and
// the first does not hold in polar coordinates (elevation over azimuth is not a projective
// image, so a roof below the eye has its lowest silhouette point between its tangent
// vertices) — which is why OH(OS)'s port of the rule, oh_os_thesis, fails for such roofs.
#pragma once

#include <cstdint>
#include <limits>

#include "engine/horizon/occlusion_horizon.hpp"
#include "engine/method.hpp"
#include "engine/spatial/quadtree.hpp"

namespace cullcheck {

// Added to tested screen-x ranges and removed from shadows' (and subtracted from shadow
// heights), in screen units (tangents), times (1 + |value|): far above the rounding of a
// projection of scene-local coordinates (about 1e-12 relative). It is a billionth of the screen
// width for ordinary fields of view; for views of a fraction of a degree it can span a few bins,
// which only costs culling (shadows shrink, tests widen).
inline constexpr double kScreenSlack = 1e-9;
// On top of it, the rounding of the coordinates themselves: a point whose coordinates (or the
// eye's) reach magnitude M is known to about M·ε, which moves its projection by about M·ε /
// depth (times 1 + |value|). A projected extent carries the largest M / depth of its points
// (`rounding`, 1/m · m = unitless); the slack is kScreenSlack + 4·ε·rounding, times 1 + |value|.
inline double screen_slack(double rounding) {
  return kScreenSlack + 4.0 * std::numeric_limits<double>::epsilon() * rounding;
}

// H(x), the occlusion horizon over the view plane's x range: the OcclusionHorizon (bins in
// blocks with min/max and lazy raises; ch. 3.1.1, Fig. 3.2's tree flattened) with its bins laid
// over the screen instead of the circle of azimuths. Bins 0 and bins−1 are margins standing for everything left and right
// of the screen and stay +inf (hidden); the screen [−half_width, +half_width] is spread over
// bins 1 .. bins−2, and every span is clamped into the margins, so no span ever wraps around.
// Same rounding as OH(OS): shadows raise only bins wholly inside their (shrunk) range, tests read
// every bin their (widened) range touches. Fails safe like OH(OS)'s horizon: a NaN screen value,
// an inverted range or a non-finite height never hides anything and a shadow with one raises
// nothing. `rounding` is the extent's coordinate rounding (screen_slack).
class ViewPlaneHorizon {
 public:
  // bins: a power of two >= 4 (std::invalid_argument otherwise).
  explicit ViewPlaneHorizon(std::uint32_t bins = 4096);

  // Nothing hidden on the screen |x| <= half_width (> 0), everything hidden beside it.
  void reset(double half_width);
  // Raises H to at least y over the bins wholly inside [x_min, x_max].
  void raise(double x_min, double x_max, double y, double rounding = 0.0);
  // min H over the bins touched by [x_min, x_max] (+inf when the range lies beside the screen;
  // −inf when a value is NaN or the range is inverted).
  double min_over(double x_min, double x_max, double rounding = 0.0);
  // True when something whose projection lies in [x_min, x_max] below y_max is hidden.
  bool hides(double x_min, double x_max, double y_max, double rounding = 0.0);

  std::uint32_t bins() const { return horizon_.bins(); }
  // The bin holding screen x (0 and bins−1: beside the screen), and its current value.
  // std::invalid_argument for a NaN x, which lies in no bin.
  std::uint32_t bin_of(double x) const;
  double bin_value(std::uint32_t bin) { return horizon_.bin_value(bin); }
  std::uint64_t take_node_visits() { return horizon_.take_node_visits(); }
  std::string check_invariants() const { return horizon_.check_invariants(); }

 private:
  // Screen x to the horizon's bin coordinate, clamped into the margins' centres.
  double to_bin_coordinate(double x) const;

  OcclusionHorizon horizon_;
  double half_width_ = 1.0;
};

class ImageSpaceHorizonCulling final : public CullingMethod {
 public:
  explicit ImageSpaceHorizonCulling(const Scene& scene, const MethodOptions& options = {});
  std::string name() const override { return "oh_is"; }
  // Not for every camera: see claims_conservative_for.
  bool claims_conservative() const override { return false; }
  // Level cameras (4 DoF: pitch == 0 and roll == 0) and omnidirectional ones (no view plane:
  // plain view-volume culling).
  bool claims_conservative_for(const Camera& camera) const override;
  CullResult cull(const Camera& camera) override;

  // The horizon as left by the last query (for tests and reports).
  ViewPlaneHorizon& horizon() { return horizon_; }
  const Quadtree& quadtree() const { return quadtree_; }

 private:
  const Scene& scene_;
  Quadtree quadtree_;
  ViewPlaneHorizon horizon_;
};

}  // namespace cullcheck
