// From-region PVS of a view cell (thesis ch. 5.1 over ch. 4's shrinking; slice-wise paper §4):
// every building visible from some eye in a convex plan polygon (a street cell) at a fixed eye
// height, in every direction. It is the union of ε-disc region PVSs (any RegionCullingMethod,
// omnidirectional) at sample points:
//
//  - boundary (as published, ch. 5.1 and Fig. 4.2): points on the cell's boundary at most 2ε
//    apart, corners included, so every boundary point lies in some sample's disc.
//    Why the boundary is enough: if an eye P inside the cell sees a point Q outside it, extend
//    the sight line through P to where it leaves the cell: forward (towards Q) when Q is below
//    the eye, backward when Q is above it. There, at B, the line runs below eye height, and the
//    sight line from B's eye to Q lies above the line P-Q (or its part inside the cell)
//    throughout; buildings stand on the ground, so it is clear too. This needs a convex cell with
//    nothing in it rising above the eye (kiosks lower than the eye are fine), which street cells
//    are; the properties check it with the oracle from interior eyes.
//  - tiled (the circle tiling of Fig. 4.9d, engine/shrinking/circle_tiling.hpp): discs centred
//    on the hexagonal lattice wherever they meet the cell. Every point of the cell is within ε of
//    a centre, so the union is conservative wherever the disc method is, with no assumption on
//    what stands in the cell; it costs more samples for a wide cell.
//
// Carrying (the incremental part): samples are visited so that each follows a neighbour, and a
// building already in the union is accepted untested by later samples
// (RegionCullingMethod::cull_region_carrying). The union is the same; the saving is reported.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "core/camera.hpp"
#include "core/shard.hpp"
#include "engine/method.hpp"

namespace cullcheck {

struct ViewCell {
  std::vector<Vec2> ring;   // convex, counter-clockwise, no repeated vertex
  double eye_height = 1.7;  // metres above the ground, for every eye of the cell
};

enum class CellSampling { boundary, tiled };
std::string_view cell_sampling_name(CellSampling s);
// Throws std::invalid_argument naming the accepted values when `name` is neither.
CellSampling parse_cell_sampling(std::string_view name);

// Points on the boundary at most 2ε apart along it, starting at each corner. Throws
// std::invalid_argument when an edge would need more than kMaxSamplesPerEdge (or a NaN count:
// a NaN vertex or ε).
inline constexpr std::size_t kMaxSamplesPerEdge = 100'000'000;
std::vector<Vec2> boundary_samples(const std::vector<Vec2>& ring, double epsilon);

// The sample points of `sampling`, in visiting order. Throws std::invalid_argument when the cell
// is not a convex counter-clockwise polygon, ε is not positive and finite, or the cell would need
// more than `max_samples` samples.
std::vector<Vec2> cell_samples(const ViewCell& cell, double epsilon, CellSampling sampling,
                               std::size_t max_samples = 1'000'000);

struct ViewCellResult {
  std::vector<ObjectId> pvs;        // sorted, the union over samples
  std::size_t samples = 0;          // samples computed (a shard's share)
  std::size_t cell_samples = 0;     // samples of the whole cell
  CullStatistics stats;             // summed over samples; cull_ms = wall time of the whole cell
  std::vector<std::size_t> sample_pvs_size;
  std::vector<ObjectId> passive;    // sorted, the union of the samples' passive targets (if any)
};

// One region method's view-cell PVSs over one scene. The union is kept by scene index (what
// cull_region_carrying reads), so building ids are indexed once here, not per cell.
class ViewCellPvs {
 public:
  // `passive_targets`: how many passive targets the method was given (set_passive_targets), so
  // that their union carries from sample to sample too; 0 when it has none.
  ViewCellPvs(RegionCullingMethod& method, const Scene& scene, std::size_t passive_targets = 0);
  // `camera` gives the eyes' clip planes (its position and orientation are ignored: each
  // sample's camera is omnidirectional at the sample, at the cell's eye height). With `carry`,
  // decisions carry from sample to sample where the method supports it (carries_known).
  // `shard` computes only its samples (the n-th sample when n mod N = K): the union of the N
  // shards' PVSs is the cell's, carried or not.
  ViewCellResult compute(const ViewCell& cell, double epsilon, CellSampling sampling, bool carry,
                         const Camera& camera = {}, Shard shard = {});

 private:
  RegionCullingMethod& method_;
  const Scene& scene_;
  std::vector<std::pair<ObjectId, std::uint32_t>> index_of_;  // (id, scene index), sorted by id
  std::vector<std::uint32_t> dense_index_of_;                 // id -> scene index, when ids are small
  std::vector<char> known_;                                   // the union so far, by scene index
  std::size_t passive_targets_;
  std::vector<char> known_passive_;                           // the passive union so far, by id
};

}  // namespace cullcheck
