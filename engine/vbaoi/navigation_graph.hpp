// VbAoI's navigable-region graph (thesis ch. 5.1, Fig. 5.1-5.2). VbAoI = visibility-based area of
// interest: a client loads only what its region may see and exchanges updates only with clients
// in regions that may see it.
//
// One node per navigable region (core/navigable_region.hpp), holding Fig. 5.2's data:
//  - id: also the node's channel id (clients in the node publish on it);
//  - coords: the region's convex ring (a client checks whether it is still inside);
//  - PVSo: the buildings visible from some eye in the region, at the avatars' eye height, in
//    every direction: the view-cell PVS (engine/shrinking/view_cell.hpp) of a from-region method;
//  - PVSn: the nodes visible from the region: those whose region, extruded to eye height as a
//    passive target (engine/shrinking/passive_targets.hpp), the same method does not hide from
//    any of the view cell's samples. PVSn is the set of channels a client in the node listens to;
//  - SNs: the neighbours (regions sharing an edge), whose data a client fetches before it may
//    enter one.
//
// Mutual visibility (the thesis: "visibility in 360 degrees is mutual"), made explicit: if a
// client at eye P in node A sees a client at eye Q in node B, the segment PQ is clear; so Q is a
// point of B's passive target visible from P, and a method conservative over A keeps B in A's
// PVSn; by the same argument from Q, A is in B's. Each direction is thus covered on its own, and
// both hold together, so PVSn may be made symmetric (B in PVSn(A) iff A in PVSn(B), so that a
// node's listeners are exactly its PVSn) by intersection: an entry one side lists and the other
// does not is an over-estimate of the listing side (a large region close by is rarely hidden from
// a small one, whose far side hides it from the large one). Union, the forgiving choice, is kept
// for methods that are not conservative. Each node itself and its neighbours (which any eye on
// the shared edge sees) are added last. The one-sided entries and the added ones are counted.
// The guarantee is only as good as the method's claim: with shrink_adjustable_thesis (refuted)
// it is not one, and the channel-grouping property measures what that costs.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/navigable_region.hpp"
#include "core/scene.hpp"
#include "engine/method.hpp"
#include "engine/shrinking/view_cell.hpp"

namespace cullcheck {

using NodeId = std::uint32_t;

struct NavigationNode {
  NodeId id = 0;                    // = channel id = index in the graph
  std::string kind;                 // the region's kind ("crossing", "street", "plaza", "free")
  std::vector<Vec2> coords;         // convex, counter-clockwise
  std::vector<ObjectId> pvs_o;      // sorted building ids
  std::vector<NodeId> pvs_n;        // sorted node ids; holds the node itself and its neighbours
  std::vector<NodeId> neighbours;   // SNs, sorted
};

// How a one-sided PVSn entry (B in raw PVSn(A), A not in raw PVSn(B)) is resolved.
enum class PvsnSymmetry { intersection, union_of_both };
std::string_view pvs_n_symmetry_name(PvsnSymmetry s);
// Throws std::invalid_argument naming the accepted values.
PvsnSymmetry parse_pvs_n_symmetry(std::string_view name);

struct NavigationGraphOptions {
  std::string method = "shrink_former";  // a region method that supports passive targets
  double epsilon = 1.4142135623730951;   // ε-disc radius of each view-cell sample (half their spacing)
  double eye_height = 1.7;               // every eye and every avatar's eye, metres
  CellSampling sampling = CellSampling::boundary;
  bool carry = true;                     // view-cell decisions carried from sample to sample
  PvsnSymmetry symmetry = PvsnSymmetry::intersection;
  unsigned threads = 1;                  // nodes computed in parallel, each thread its own method
  MethodOptions method_options;
};

struct NavigationGraphStatistics {
  std::vector<double> node_ms;           // wall time of each node's view cell
  std::uint64_t samples = 0;             // view-cell samples over all nodes
  std::uint64_t pvs_n_one_sided = 0;     // raw entries without their mirror (dropped or mirrored by `symmetry`)
  std::uint64_t pvs_n_added_neighbours = 0;  // neighbours (or the node itself) the method did not list
  double build_seconds = 0.0;            // wall time of the whole graph
};

struct NavigationGraph {
  std::vector<NavigationNode> nodes;
  NavigationGraphOptions options;
  bool method_claims_conservative = false;
  NavigationGraphStatistics stats;
};

// Each region extruded from the ground to `eye_height`, id = region id: the passive targets whose
// visibility from a view cell puts a node in its PVSn (what another client's avatar may be).
Scene navigable_region_targets(const std::vector<NavigableRegion>& regions, double eye_height);

// Makes the nodes' raw PVSn lists (sorted, by node index) symmetric in place by `symmetry`, as
// build_navigation_graph does before it adds each node and its neighbours; returns how many
// entries were one-sided (B in A's raw list, A not in B's).
// Who lists each node (the lists' mirror) is gathered for a block of nodes at a time, holding
// about `mirror_entries` entries, and merged with the block's own lists, which change at once
// (intersection drops the entries the mirror lacks, union adds the listers the list lacks).
// Each list is read once in all: sorted, it gives each block its entries from where the last
// stopped. At Boston's size (193,326 nodes, about 690 million raw entries, 2.8 GB) a whole mirror
// doubled the graph's peak memory; a binary search per entry in the other node's list (random reads over
// all of them) took 3x as long on two threads as these passes on one (a 1.6 km square of Boston,
// 12,148 nodes). Any budget gives the same lists.
inline constexpr std::size_t kMirrorEntries = std::size_t{1} << 25;  // 128 MB of mirror at a time
std::uint64_t make_pvs_n_symmetric(std::vector<NavigationNode>& nodes, PvsnSymmetry symmetry,
                                   std::size_t mirror_entries = kMirrorEntries);

// One node's visibility as the method computes it, before the graph adds symmetry and
// neighbours: the view-cell result of region `index` (PVSo in .pvs, the raw PVSn in .passive).
// Each instance holds its own method (one per thread). Throws like build_navigation_graph.
class NodeVisibility {
 public:
  NodeVisibility(const Scene& scene, const std::vector<NavigableRegion>& regions, const NavigationGraphOptions& options);
  ~NodeVisibility();
  ViewCellResult compute(std::size_t index);
  bool method_claims_conservative() const;

 private:
  const std::vector<NavigableRegion>& regions_;
  NavigationGraphOptions options_;
  std::unique_ptr<RegionCullingMethod> method_;
  std::unique_ptr<ViewCellPvs> cells_;
};

// Throws std::invalid_argument when the regions' ids are not their indices, a region is not a
// valid view cell, a neighbour id is out of range, or the method is unknown or cannot test
// passive targets.
NavigationGraph build_navigation_graph(const Scene& scene, const std::vector<NavigableRegion>& regions,
                                       const NavigationGraphOptions& options = {});

// A hash of every node's PVSo, PVSn and neighbours, in node order: two graphs with the same digest
// hold the same sets (how a faster build shows it changed nothing, issue 17).
std::uint64_t graph_digest(const NavigationGraph& graph);

// The graph invariants (issue: neighbour symmetry, each PVSn holds its node and its neighbours,
// channel ids unique), plus sorted lists and a symmetric PVSn. One line per problem; empty when
// the graph is sound.
std::vector<std::string> graph_invariant_violations(const NavigationGraph& graph);

// The node a plan point lies in, looking first at `hint` and its neighbours (a walking client's
// check, thesis Fig. 5.3), then at every node; -1 when none. Points on a shared edge belong to
// the first node found. `tolerance` (metres) admits points that far outside a ring.
std::int64_t locate_node(const NavigationGraph& graph, Vec2 point, std::int64_t hint = -1, double tolerance = 1e-9);

}  // namespace cullcheck
