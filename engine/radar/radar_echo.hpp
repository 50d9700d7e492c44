// Radar echo generation over terrain (thesis ch. 3.3.2): the triangles a transmitter sees over
// 360 degrees (or a sector), by the object-space occlusion horizon over a TriangleGrid.
//
// Both rules share the sweep: cells from front to back (best-first on their nearest plan
// distance, flooding from the transmitter's cell to neighbours, so every cell of the sector is
// met in order of distance, hidden or not); the transmitter's own cell first (step 1), whose
// triangles facing it are all in the PVS; then each cell tested against the horizon H over its
// azimuth span (step 2), and a visible cell's triangles, highest first, tested in turn until
// the next one cannot clear min H over the cell; a visible triangle joins the PVS and its
// shadow raises H. Triangles facing away from the transmitter (it lies below their plane) are
// never in the PVS: from above a height field, a line of sight first meets a surface from
// above (edge-on ones are kept by the conservative test; a building's walls face outward). The
// PVS is the set of triangle numbers (core/terrain.hpp, then core/terrain_scene.hpp's for the
// buildings), ascending.
//
// The rules differ where the thesis's choices are not conservative:
//   thesis        as published. A cell's highest possible elevation is its top at C2, the
//                 cell's nearest point; a triangle is visible when a vertex's elevation clears
//                 min H over the triangle's span; its shadow's elevation is β_min, the lower of
//                 the elevations of its two extreme-azimuth vertices (Fig. 3.12-3.13); shadows
//                 raise H at once.
//   conservative  a cell's (and a triangle's) highest elevation bounded over its whole distance
//                 range (top at the nearest point when above the eye, at the farthest when
//                 below: a radar on a mast looks down on nearly everything); a triangle tested
//                 per cell on its part there (the cell's box clipped to the triangle's plan
//                 box); its shadow's elevation bounded below over the whole triangle (its
//                 lowest vertex at the nearest distance when below the eye, the farthest when
//                 above); shadows wait until the sweep has passed the triangle's farthest
//                 point (Downs et al.'s rule, engine/horizon/horizon_sweep.hpp). Why it is
//                 conservative: a line of sight at an azimuth inside a visible triangle's span
//                 crosses the triangle's plan; if it passes below the triangle there it went
//                 under the surface before, so what lies beyond the triangle at a lower
//                 elevation than every point of the triangle is hidden. It needs the
//                 transmitter above the terrain and no holes the line could pass under the
//                 surface through: on a terrain with holes, shadows are not used. With
//                 buildings (core/terrain_scene.hpp) the transmitter must stand outside them
//                 (or above the roof): a line under a roof triangle's far chain is inside the
//                 prism (its walls reach down to the lowest ground under it) or under the
//                 ground, so the argument holds; and a wall triangle stands for its whole wall,
//                 solid from the buried base to the roof along its plan segment, so its shadow
//                 is the roof line's (a roof above the eye faces away and casts none).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/geometry.hpp"
#include "engine/horizon/horizon_sweep.hpp"
#include "engine/horizon/occlusion_horizon.hpp"
#include "engine/radar/cell_front.hpp"
#include "engine/radar/triangle_grid.hpp"

namespace cullcheck::radar {

enum class RadarRule { thesis, conservative };

// The four choices that make a rule, so that each of the thesis's can be checked on its own
// with the others conservative (the claims ledger does).
enum class CellBound { nearest_point, distance_range };   // C2 alone, or the cell's distance range
enum class TriangleTest { vertices, bound };              // a vertex clears H, or the bound over the part in the cell
enum class ShadowBound { beta_min, far_chain };           // Fig. 3.13's β_min, or the far chain's lower bound
enum class ShadowMerge { immediate, delayed };            // raise H at once, or when the sweep has passed the triangle
struct RadarRules {
  CellBound cell = CellBound::distance_range;
  TriangleTest triangle = TriangleTest::bound;
  ShadowBound shadow = ShadowBound::far_chain;
  ShadowMerge merge = ShadowMerge::delayed;
  static RadarRules of(RadarRule rule);
  friend bool operator==(const RadarRules&, const RadarRules&) = default;
};

// The rules by name: "thesis" and "conservative", and each of the thesis's four choices alone
// with the other three conservative, so the claims ledger can say which of them loses triangles:
// "thesis-cell-bound" (C2), "thesis-vertex-test", "thesis-beta-min", "thesis-immediate-merge".
struct NamedRules {
  std::string name;
  RadarRules rules;
  bool claims_conservative = true;  // every variant claims it: each is checked, none trusted
};
const std::vector<NamedRules>& named_rules();
std::optional<RadarRules> rules_named(std::string_view name);

// Azimuths [centre - width / 2, centre + width / 2]; a width of 2π or more is the full circle.
struct Sector {
  double centre = 0.0;
  double width = kTwoPi;
};
AzimuthSpan sector_span(const Sector& s);

struct EchoStatistics {
  std::size_t cells_tested = 0;      // cells of the sector met by the sweep and tested against H
  std::size_t cells_visible = 0;     // of those, not hidden
  std::size_t triangles_tested = 0;  // triangle tests in visible cells (a triangle in k cells may count k times)
  std::size_t shadows = 0;           // shadows merged into H
};

struct Echo {
  std::vector<std::uint32_t> visible;  // triangle numbers, ascending
  EchoStatistics stats;
};

// Occluders shrunk for an echo from a region (engine/radar/region_echo.hpp): each triangle's
// shadow cast at the higher of its floor (a height under which the solid eroded by `radius` in
// plan lies all over the triangle's plan) and its far chain's lowest vertex less its drop (how
// far that solid can lie below the chain); eyes anywhere within `radius` of the echo's eye,
// from z_low up to its height, count for facing.
struct ShrunkOccluders {
  const std::vector<double>* floors = nullptr;  // per triangle, -inf: none
  const std::vector<double>* drops = nullptr;   // per triangle, +inf: none
  double radius = 0.0;
  double z_low = 0.0;
};

class RadarEcho {
 public:
  RadarEcho(const TriangleGrid& grid, RadarRule rule, std::uint32_t horizon_bins = 16384);
  RadarEcho(const TriangleGrid& grid, const RadarRules& rules, std::uint32_t horizon_bins = 16384);
  // The triangles visible from `transmitter` (plan position and height, scene-local metres)
  // within `sector`. The transmitter must lie over the grid.
  Echo compute(Vec3 transmitter, const Sector& sector = {});
  // The conservative rule's sweep from `transmitter` with every shadow cast by a shrunk occluder
  // (region_echo.hpp says why that serves every eye within shrunk.radius); throws
  // std::invalid_argument for another rule or floors that are not one per triangle.
  Echo compute_shrunk(Vec3 transmitter, const Sector& sector, const ShrunkOccluders& shrunk);
  const RadarRules& rules() const { return rules_; }

 private:
  Echo sweep(Vec3 eye, const Sector& sector, const ShrunkOccluders* shrunk);
  bool faces(std::uint32_t t, Vec3 eye, const ShrunkOccluders* shrunk) const;

  const TriangleGrid& grid_;
  RadarRules rules_;
  OcclusionHorizon horizon_;
  ShadowQueue queue_;
  CellFront front_;
  std::vector<std::uint32_t> seen_;     // per triangle: the query that found it visible
  bool holes_;  // some triangle is absent: the conservative rule casts no shadows
  std::uint32_t query_ = 0;
};

}  // namespace cullcheck::radar
