#include "engine/vbaoi/navigation_graph.hpp"
#include "core/elapsed.hpp"
#include "core/progress.hpp"
#include "core/random.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>

namespace cullcheck {
namespace {

void check_regions(const std::vector<NavigableRegion>& regions) {
  for (std::size_t i = 0; i < regions.size(); ++i) {
    if (regions[i].id != i)
      throw std::invalid_argument("navigation graph: region " + std::to_string(i) + " has id " +
                                  std::to_string(regions[i].id) + "; ids must be the regions' indices");
    for (std::uint32_t n : regions[i].neighbours)
      if (n >= regions.size() || n == i)
        throw std::invalid_argument("navigation graph: region " + std::to_string(i) + " lists neighbour " +
                                    std::to_string(n) + ", not another region");
  }
}

void sorted_insert(std::vector<NodeId>& v, NodeId x, std::uint64_t& added) {
  const auto it = std::lower_bound(v.begin(), v.end(), x);
  if (it != v.end() && *it == x) return;
  v.insert(it, x);
  ++added;
}

}  // namespace

std::string_view pvs_n_symmetry_name(PvsnSymmetry s) { return s == PvsnSymmetry::intersection ? "intersection" : "union"; }

PvsnSymmetry parse_pvs_n_symmetry(std::string_view name) {
  if (name == "intersection") return PvsnSymmetry::intersection;
  if (name == "union") return PvsnSymmetry::union_of_both;
  throw std::invalid_argument("unknown PVSn symmetry '" + std::string(name) + "' (known: intersection, union)");
}

std::uint64_t make_pvs_n_symmetric(std::vector<NavigationNode>& nodes, PvsnSymmetry symmetry, std::size_t mirror_entries) {
  const std::size_t n = nodes.size();
  std::vector<std::size_t> cursor(n, 0);    // per list: its first entry not yet given to a block
  std::vector<std::vector<NodeId>> mirror;  // per node of the block: the nodes that list it, ascending
  std::vector<NodeId> judged;               // scratch: a list's kept entries, or the listers it lacks
  std::uint64_t one_sided = 0;
  for (std::size_t first = 0; first < n;) {
    // A block whose own lists hold about the budget; a symmetric graph's mirror holds as many.
    std::size_t last = first, entries = 0;
    do entries += nodes[last++].pvs_n.size();
    while (last < n && entries + nodes[last].pvs_n.size() <= mirror_entries);
    mirror.assign(last - first, {});
    for (std::size_t a = 0; a < n; ++a) {
      const std::vector<NodeId>& listed = nodes[a].pvs_n;
      std::size_t& k = cursor[a];
      for (; k < listed.size() && listed[k] < last; ++k) mirror[listed[k] - first].push_back(static_cast<NodeId>(a));
    }
    for (std::size_t b = first; b < last; ++b) {
      std::vector<NodeId>& own = nodes[b].pvs_n;
      const std::vector<NodeId>& listers = mirror[b - first];
      judged.clear();
      if (symmetry == PvsnSymmetry::intersection) {
        // Copied back over the list, keeping its capacity: a smaller copy of each list would be
        // allocated beside the memory the larger ones leave behind (1.1 GB more at Boston's size).
        std::set_intersection(own.begin(), own.end(), listers.begin(), listers.end(), std::back_inserter(judged));
        one_sided += own.size() - judged.size();
        own.assign(judged.begin(), judged.end());
      } else {
        std::set_difference(listers.begin(), listers.end(), own.begin(), own.end(), std::back_inserter(judged));
        one_sided += judged.size();
        const std::size_t before = own.size();
        own.insert(own.end(), judged.begin(), judged.end());
        std::inplace_merge(own.begin(), own.begin() + static_cast<std::ptrdiff_t>(before), own.end());
      }
      // Changed at once, and no later block's judgement moves: an entry dropped here (B -> T, T
      // not listing B) is never one T is judged on, and an entry added here (B -> A, A listing
      // B) finds its mirror already in A's list. Only this list's place in its entries moves.
      cursor[b] = static_cast<std::size_t>(std::lower_bound(own.begin(), own.end(), static_cast<NodeId>(last)) - own.begin());
    }
    first = last;
  }
  return one_sided;
}

Scene navigable_region_targets(const std::vector<NavigableRegion>& regions, double eye_height) {
  Scene targets;
  targets.provenance.generator = "navigable regions";
  for (const NavigableRegion& r : regions) {
    Building b;
    b.id = r.id;
    b.footprint = r.ring;
    b.height = eye_height;
    finish_building(b);
    targets.buildings.push_back(std::move(b));
  }
  return targets;
}

NodeVisibility::NodeVisibility(const Scene& scene, const std::vector<NavigableRegion>& regions,
                               const NavigationGraphOptions& options)
    : regions_(regions), options_(options) {
  check_regions(regions);
  if (!(options.eye_height > 0.0) || !std::isfinite(options.eye_height))
    throw std::invalid_argument("navigation graph: eye height must be positive and finite");
  // Refuse a bad cell or ε before any work.
  for (const NavigableRegion& r : regions) cell_samples(ViewCell{r.ring, options.eye_height}, options.epsilon, options.sampling);
  method_ = make_region_method(options.method, scene, options.method_options);
  method_->set_passive_targets(navigable_region_targets(regions, options.eye_height));  // throws, naming a method that cannot
  cells_ = std::make_unique<ViewCellPvs>(*method_, scene, regions.size());
}

NodeVisibility::~NodeVisibility() = default;

ViewCellResult NodeVisibility::compute(std::size_t index) {
  return cells_->compute(ViewCell{regions_.at(index).ring, options_.eye_height}, options_.epsilon, options_.sampling,
                         options_.carry);
}

bool NodeVisibility::method_claims_conservative() const { return method_->claims_conservative(); }

NavigationGraph build_navigation_graph(const Scene& scene, const std::vector<NavigableRegion>& regions,
                                       const NavigationGraphOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  NavigationGraph graph;
  graph.options = options;
  graph.nodes.resize(regions.size());
  graph.stats.node_ms.assign(regions.size(), 0.0);
  // The first worker is built here, so that bad input is refused before threads start.
  std::vector<std::unique_ptr<NodeVisibility>> workers;
  workers.push_back(std::make_unique<NodeVisibility>(scene, regions, options));
  graph.method_claims_conservative = workers[0]->method_claims_conservative();
  const unsigned threads = std::max(1u, std::min<unsigned>(options.threads, static_cast<unsigned>(regions.size())));

  Progress progress("VbAoI graph: the view cell of every navigable region", regions.size(), "nodes");
  std::atomic<std::size_t> next{0};
  std::atomic<std::uint64_t> samples{0};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  auto work = [&](std::size_t w) {
    try {
      if (!workers[w]) workers[w] = std::make_unique<NodeVisibility>(scene, regions, options);
      for (std::size_t i = next++; i < regions.size(); i = next++) {
        const NavigableRegion& r = regions[i];
        const ViewCellResult v = workers[w]->compute(i);
        NavigationNode& node = graph.nodes[i];
        node.id = r.id;
        node.kind = r.kind;
        node.coords = r.ring;
        node.pvs_o = v.pvs;
        node.pvs_n.assign(v.passive.begin(), v.passive.end());
        node.neighbours = r.neighbours;
        std::sort(node.neighbours.begin(), node.neighbours.end());
        graph.stats.node_ms[i] = v.stats.cull_ms;
        samples += v.samples;
        progress.advance();
      }
    } catch (...) {
      const std::lock_guard lock(failure_mutex);
      if (!failure) failure = std::current_exception();
      next = regions.size();
    }
  };
  workers.resize(threads);
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(work, t);
  work(0);
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
  graph.stats.samples = samples;

  // Symmetric PVSn (header: intersection or union), then each node itself and its neighbours.
  graph.stats.pvs_n_one_sided = make_pvs_n_symmetric(graph.nodes, options.symmetry);
  for (NavigationNode& n : graph.nodes) {
    sorted_insert(n.pvs_n, n.id, graph.stats.pvs_n_added_neighbours);
    for (NodeId m : n.neighbours) sorted_insert(n.pvs_n, m, graph.stats.pvs_n_added_neighbours);
  }
  // Adding a neighbour A to B's list must add B to A's as well: neighbours are symmetric (checked
  // by graph_invariant_violations), so the second pass kept PVSn symmetric.
  graph.stats.build_seconds = seconds_since(start);
  return graph;
}

std::uint64_t graph_digest(const NavigationGraph& graph) {
  std::uint64_t h = 0x475241504855ULL;  // "GRAPHU"
  for (const NavigationNode& n : graph.nodes) {
    h = hash_mix(h, n.id);
    for (const auto* list : {&n.pvs_o, &n.pvs_n, &n.neighbours}) {
      h = hash_mix(h, list->size());
      for (std::uint32_t x : *list) h = hash_mix(h, x);
    }
  }
  return h;
}

std::vector<std::string> graph_invariant_violations(const NavigationGraph& graph) {
  std::vector<std::string> out;
  const std::size_t n = graph.nodes.size();
  auto name = [](std::size_t i) { return "node " + std::to_string(i); };
  auto contains = [](const std::vector<NodeId>& v, NodeId x) { return std::binary_search(v.begin(), v.end(), x); };
  for (std::size_t i = 0; i < n; ++i) {
    const NavigationNode& node = graph.nodes[i];
    if (node.id != i) out.push_back(name(i) + ": channel id " + std::to_string(node.id) + " is not its index (ids must be unique)");
    if (!std::is_sorted(node.neighbours.begin(), node.neighbours.end()) ||
        std::adjacent_find(node.neighbours.begin(), node.neighbours.end()) != node.neighbours.end())
      out.push_back(name(i) + ": neighbours not sorted and unique");
    if (!std::is_sorted(node.pvs_n.begin(), node.pvs_n.end()) ||
        std::adjacent_find(node.pvs_n.begin(), node.pvs_n.end()) != node.pvs_n.end())
      out.push_back(name(i) + ": PVSn not sorted and unique");
    if (!std::is_sorted(node.pvs_o.begin(), node.pvs_o.end()) ||
        std::adjacent_find(node.pvs_o.begin(), node.pvs_o.end()) != node.pvs_o.end())
      out.push_back(name(i) + ": PVSo not sorted and unique");
    if (!contains(node.pvs_n, static_cast<NodeId>(i))) out.push_back(name(i) + ": PVSn lacks the node itself");
    for (NodeId m : node.neighbours) {
      if (m >= n || m == i) {
        out.push_back(name(i) + ": neighbour " + std::to_string(m) + " is not another node");
        continue;
      }
      if (!contains(graph.nodes[m].neighbours, static_cast<NodeId>(i)))
        out.push_back(name(i) + ": neighbour " + std::to_string(m) + " does not list it back");
      if (!contains(node.pvs_n, m)) out.push_back(name(i) + ": PVSn lacks neighbour " + std::to_string(m));
    }
    for (NodeId m : node.pvs_n) {
      if (m >= n) {
        out.push_back(name(i) + ": PVSn lists " + std::to_string(m) + ", not a node");
        continue;
      }
      if (!contains(graph.nodes[m].pvs_n, static_cast<NodeId>(i)))
        out.push_back(name(i) + ": sees node " + std::to_string(m) + " which does not see it back");
    }
  }
  return out;
}

std::int64_t locate_node(const NavigationGraph& graph, Vec2 p, std::int64_t hint, double tolerance) {
  if (hint >= 0 && static_cast<std::size_t>(hint) < graph.nodes.size()) {
    const NavigationNode& h = graph.nodes[static_cast<std::size_t>(hint)];
    if (ring_contains(h.coords, p, tolerance)) return hint;
    for (NodeId m : h.neighbours)
      if (ring_contains(graph.nodes[m].coords, p, tolerance)) return m;
  }
  for (const NavigationNode& n : graph.nodes)
    if (ring_contains(n.coords, p, tolerance)) return n.id;
  return -1;
}

}  // namespace cullcheck
