#include "reports/shard_merge.hpp"

#include <algorithm>
#include <numeric>

#include "core/errors.hpp"

namespace cullcheck {

namespace {

InputError disagree(std::size_t shard, const std::string& what, const std::string& problem) {
  return InputError("shard " + std::to_string(shard), what, problem);
}

// The order in which entries of several shards are taken: by frame number, then by shard (a
// frame is checked in one shard only, so ties are a shard's own consecutive entries).
struct Entry {
  std::size_t frame, shard, index;
  bool operator<(const Entry& o) const { return std::tie(frame, shard, index) < std::tie(o.frame, o.shard, o.index); }
};
template <class FrameOf>
std::vector<Entry> interleave(std::size_t shards, FrameOf frames_of) {
  std::vector<Entry> all;
  for (std::size_t s = 0; s < shards; ++s) {
    const std::vector<std::size_t>& frames = frames_of(s);
    for (std::size_t k = 0; k < frames.size(); ++k) all.push_back({frames[k], s, k});
  }
  std::stable_sort(all.begin(), all.end());
  return all;
}
template <class T>
void take(std::vector<T>& out, const std::vector<T>& from, std::size_t index, std::size_t shard, const std::string& what) {
  if (index >= from.size()) throw disagree(shard, what, "has fewer entries than checked frames");
  out.push_back(from[index]);
}

// The first `limit` violations of several shards, in frame order (each shard kept its first).
std::vector<Violation> first_violations(const std::vector<const std::vector<Violation>*>& lists, std::size_t limit) {
  std::vector<Violation> all;
  for (const auto* list : lists) all.insert(all.end(), list->begin(), list->end());
  std::stable_sort(all.begin(), all.end(), [](const Violation& a, const Violation& b) { return a.frame < b.frame; });
  if (all.size() > limit) all.resize(limit);
  return all;
}

ViolationTally merge_tallies(const std::vector<const ViolationTally*>& tallies, std::size_t limit) {
  ViolationTally out;
  std::vector<const std::vector<Violation>*> kept;
  for (const ViolationTally* t : tallies) {
    out.count += t->count;
    out.frames += t->frames;
    kept.push_back(&t->kept);
  }
  out.kept = first_violations(kept, limit);
  return out;
}

void same(bool equal, std::size_t shard, const std::string& what, const std::string& problem) {
  if (!equal) throw disagree(shard, what, problem);
}

MethodRun merge_run(const std::vector<PathVerification>& shards, std::size_t m, std::size_t max_replays) {
  const MethodRun& first = shards[0].runs[m];
  MethodRun out = first;  // per frame: shard 0's (the others agree, times aside)
  for (std::size_t s = 1; s < shards.size(); ++s) {
    const MethodRun& r = shards[s].runs[m];
    const std::string what = "run " + first.method;
    same(r.method == first.method, s, what, "is method " + r.method + " in this shard");
    same(r.answered_frames == first.answered_frames, s, what, "answered other frames than in shard 0");
    same(r.pvs_size == first.pvs_size, s, what,
         "gave other PVS sizes than in shard 0: the method is not deterministic, or the shards did not run the same input");
    same(r.frames_differing_from_reference == first.frames_differing_from_reference && r.frames_equal_to == first.frames_equal_to,
         s, what, "compares differently with the reference method than in shard 0");
  }
  out.checked_pvs_size.clear(), out.witnessed_size.clear(), out.checked_frames.clear();
  for (const Entry& e : interleave(shards.size(), [&](std::size_t s) -> const auto& { return shards[s].runs[m].checked_frames; })) {
    const MethodRun& r = shards[e.shard].runs[m];
    out.checked_frames.push_back(e.frame);
    take(out.checked_pvs_size, r.checked_pvs_size, e.index, e.shard, first.method + ".checked_pvs_size");
    take(out.witnessed_size, r.witnessed_size, e.index, e.shard, first.method + ".witnessed_size");
  }
  out.misdrawn_pixels.clear(), out.blob_per_frame.clear(), out.pixel_frames.clear();
  for (const Entry& e : interleave(shards.size(), [&](std::size_t s) -> const auto& { return shards[s].runs[m].pixel_frames; })) {
    const MethodRun& r = shards[e.shard].runs[m];
    out.pixel_frames.push_back(e.frame);
    take(out.misdrawn_pixels, r.misdrawn_pixels, e.index, e.shard, first.method + ".misdrawn_pixels");
    take(out.blob_per_frame, r.blob_per_frame, e.index, e.shard, first.method + ".blob_per_frame");
  }
  out.snapshot.reset();
  out.witness_recheck = {};
  out.misdrawn_total = out.error_frames = out.largest_blob = out.most_misdrawn = out.frames_over_budget = 0;
  out.frames_claimed = 0;
  std::vector<const FrameSnapshot*> snapshots;
  std::vector<const std::vector<Violation>*> over;
  std::vector<const ViolationTally*> every, claimed;
  for (const PathVerification& shard : shards) {
    const MethodRun& r = shard.runs[m];
    if (r.snapshot) snapshots.push_back(&*r.snapshot);
    out.witness_recheck += r.witness_recheck;
    out.misdrawn_total += r.misdrawn_total;
    out.error_frames += r.error_frames;
    out.largest_blob = std::max(out.largest_blob, r.largest_blob);
    out.most_misdrawn = std::max(out.most_misdrawn, r.most_misdrawn);
    out.frames_over_budget += r.frames_over_budget;
    out.frames_claimed += r.frames_claimed;
    over.push_back(&r.over_budget);
    every.push_back(&r.every_frame);
    claimed.push_back(&r.claimed_frames);
  }
  // The worst frame, the earliest of equally bad ones, as one run keeps it.
  std::stable_sort(snapshots.begin(), snapshots.end(), [](const auto* a, const auto* b) { return a->frame < b->frame; });
  for (const FrameSnapshot* s : snapshots)
    if (!out.snapshot || worse_frame(*s, *out.snapshot)) out.snapshot = *s;
  out.over_budget = first_violations(over, max_replays);
  out.every_frame = merge_tallies(every, max_replays);
  out.claimed_frames = merge_tallies(claimed, max_replays);
  settle_violations(out);
  return out;
}

RegionRun merge_region(const std::vector<PathVerification>& shards, std::size_t m, std::size_t max_replays) {
  const RegionRun& first = shards[0].regions[m];
  RegionRun out = first;
  for (std::size_t s = 1; s < shards.size(); ++s) {
    const RegionRun& r = shards[s].regions[m];
    same(r.method == first.method && r.radius == first.radius && r.turn == first.turn && r.on_tiling == first.on_tiling, s,
         "region run " + first.method, "is another region run in this shard");
    same(r.pvs_size == first.pvs_size && r.compute_ms.size() == first.compute_ms.size(), s, "region run " + first.method,
         "gave other PVS sizes than in shard 0");
  }
  out.checked_pvs_size.clear(), out.witnessed_size.clear(), out.checked_frames.clear();
  for (const Entry& e : interleave(shards.size(), [&](std::size_t s) -> const auto& { return shards[s].regions[m].checked_frames; })) {
    const RegionRun& r = shards[e.shard].regions[m];
    out.checked_frames.push_back(e.frame);
    take(out.checked_pvs_size, r.checked_pvs_size, e.index, e.shard, first.method + ".checked_pvs_size");
    take(out.witnessed_size, r.witnessed_size, e.index, e.shard, first.method + ".witnessed_size");
  }
  out.violation_count = out.frames_with_violations = 0;
  out.witness_recheck = {};
  std::vector<const std::vector<Violation>*> kept;
  for (const PathVerification& shard : shards) {
    const RegionRun& r = shard.regions[m];
    out.violation_count += r.violation_count;
    out.frames_with_violations += r.frames_with_violations;
    out.witness_recheck += r.witness_recheck;
    kept.push_back(&r.violations);
  }
  out.violations = first_violations(kept, max_replays);
  return out;
}

}  // namespace

std::string first_difference(const nlohmann::json& a, const nlohmann::json& b) {
  if (!a.is_object() || !b.is_object()) return "";
  for (const auto& [key, value] : a.items())
    if (!b.contains(key) || b[key] != value) return key;
  for (const auto& [key, value] : b.items())
    if (!a.contains(key)) return key;
  return "";
}

std::vector<const nlohmann::json*> shards_in_order(const std::vector<nlohmann::json>& documents, const std::vector<std::string>& names,
                                                   std::vector<std::string>* names_in_order) {
  using nlohmann::json;
  if (documents.empty()) throw InputError("merge", "shards", "no shard files given");
  std::vector<const json*> by_index(documents.size(), nullptr);
  std::vector<std::string> name_of(documents.size());
  for (std::size_t k = 0; k < documents.size(); ++k) {
    const json& d = documents[k];
    if (!d.is_object() || !d.contains("shard") || !d["shard"].is_object())
      throw InputError(names[k], "shard", "is missing: not a shard file (write one with --shard K/N)");
    const json& s = d["shard"];
    if (!s.contains("index") || !s.contains("count") || !s["index"].is_number_unsigned() || !s["count"].is_number_unsigned())
      throw InputError(names[k], "shard", "has no index and count");
    const std::size_t index = s["index"], count = s["count"];
    if (count != documents.size())
      throw InputError(names[k], "shard.count", "is " + std::to_string(count) + ", but " + std::to_string(documents.size()) +
                                                    " shard files were given: every shard of the run is needed, once");
    if (index >= count) throw InputError(names[k], "shard.index", std::to_string(index) + " is not below the count");
    if (by_index[index])
      throw InputError(names[k], "shard.index", "shard " + std::to_string(index) + " is given twice (also " + name_of[index] + ")");
    by_index[index] = &d;
    name_of[index] = names[k];
  }
  const json& identity = (*by_index[0])["shard"].value("identity", json());
  for (std::size_t k = 1; k < by_index.size(); ++k)
    if ((*by_index[k])["shard"].value("identity", json()) != identity)
      throw InputError(name_of[k], "shard.identity",
                       "differs from shard 0's (" + name_of[0] + ") in '" +
                           first_difference(identity, (*by_index[k])["shard"].value("identity", json())) +
                           "': the shards were run with other flags");
  if (names_in_order) *names_in_order = std::move(name_of);
  return by_index;
}

PathVerification merge_verifications(const std::vector<PathVerification>& shards, std::size_t max_replays) {
  if (shards.empty()) throw InputError("shards", "", "none given");
  const PathVerification& first = shards[0];
  const std::size_t stride = std::max<std::size_t>(1, first.oracle.oracle_stride);
  for (std::size_t s = 0; s < shards.size(); ++s) {
    const PathVerification& v = shards[s];
    same(v.runs.size() == first.runs.size() && v.regions.size() == first.regions.size(), s, "runs",
         "has other methods than shard 0");
    same(v.frames_run == first.frames_run, s, "frames_run", "ran other frames than shard 0 (an outside subject failed in one)");
    same(v.skipped_methods == first.skipped_methods, s, "skipped_methods", "skipped other methods than shard 0");
    same(v.oracle.oracle_stride == first.oracle.oracle_stride && v.oracle.density == first.oracle.density, s, "oracle",
         "ran the oracle with other settings than shard 0");
    same(v.pixels.enabled == first.pixels.enabled, s, "pixels", "ran the pixel oracle where shard 0 did not, or the reverse");
    // Each shard checked exactly its share: the n-th checked frame belongs to shard n mod N.
    const Shard mine{s, shards.size()};
    for (std::size_t f : v.checked_frames)
      same(f % stride == 0 && mine.owns(f / stride), s, "checked_frames",
           "frame " + std::to_string(f) + " is not in shard " + mine.text() + "'s share (every " + std::to_string(stride) +
               "th frame from 0, the n-th in shard n mod " + std::to_string(shards.size()) + ")");
  }
  PathVerification out;
  for (std::size_t m = 0; m < first.runs.size(); ++m) out.runs.push_back(merge_run(shards, m, max_replays));
  for (std::size_t m = 0; m < first.regions.size(); ++m) out.regions.push_back(merge_region(shards, m, max_replays));
  for (const Entry& e : interleave(shards.size(), [&](std::size_t s) -> const auto& { return shards[s].checked_frames; })) {
    out.checked_frames.push_back(e.frame);
    take(out.checked_visible, shards[e.shard].checked_visible, e.index, e.shard, "checked_visible");
  }
  out.oracle = first.oracle;
  out.oracle.frames_checked = out.oracle.frames_exact_2d = out.oracle.frames_ray_sampling = 0;
  out.oracle.rays_cast = out.oracle.grazing_rays = out.oracle.rays_skipped = 0;
  out.oracle.seconds = out.oracle.sampling_seconds = 0.0;
  out.oracle.witness_recheck = {};
  out.pixels = first.pixels;
  out.pixels.frames = 0, out.pixels.rays = 0, out.pixels.seconds = 0.0;
  for (const PathVerification& v : shards) {
    out.oracle.frames_checked += v.oracle.frames_checked;
    out.oracle.frames_exact_2d += v.oracle.frames_exact_2d;
    out.oracle.frames_ray_sampling += v.oracle.frames_ray_sampling;
    out.oracle.rays_cast += v.oracle.rays_cast;
    out.oracle.grazing_rays += v.oracle.grazing_rays;
    out.oracle.rays_skipped += v.oracle.rays_skipped;
    out.oracle.seconds += v.oracle.seconds;
    out.oracle.sampling_seconds += v.oracle.sampling_seconds;
    out.oracle.witness_recheck += v.oracle.witness_recheck;
    out.pixels.frames += v.pixels.frames;
    out.pixels.rays += v.pixels.rays;
    out.pixels.seconds += v.pixels.seconds;
  }
  out.skipped_methods = first.skipped_methods;
  out.frames_run = first.frames_run;
  out.aborted = first.aborted;
  return out;
}

std::vector<ClaimCheck> merge_claims(const std::vector<std::vector<ClaimCheck>>& shards) {
  if (shards.empty()) return {};
  std::vector<ClaimCheck> out = shards[0];
  for (std::size_t s = 1; s < shards.size(); ++s) {
    same(shards[s].size() == out.size(), s, "claims", "searched other claims than shard 0");
    for (std::size_t k = 0; k < out.size(); ++k) {
      ClaimCheck& c = out[k];
      const ClaimCheck& p = shards[s][k];
      same(p.id == c.id, s, "claims", "has claim " + p.id + " where shard 0 has " + c.id);
      c.frames_checked += p.frames_checked;
      c.violations += p.violations;
      c.search_seconds += p.search_seconds;
      if (!p.holds && (c.holds || p.counterexample_scene < c.counterexample_scene)) {
        c.holds = false;
        c.counterexample_replay = p.counterexample_replay;
        c.counterexample_detail = p.counterexample_detail;
        c.counterexample_scene = p.counterexample_scene;
      }
    }
  }
  return out;
}

std::vector<KnobRow> merge_knob_rows(const std::vector<std::vector<KnobRow>>& shards) {
  if (shards.empty()) return {};
  std::vector<KnobRow> out = shards[0];
  for (std::size_t k = 0; k < out.size(); ++k) {
    KnobRow& row = out[k];
    const std::string what = "knob sweep " + row.knob + "=" + std::to_string(row.value) + " " + row.method;
    row.checked_frames.clear(), row.checked_pvs.clear(), row.witnessed.clear();
    row.misses = 0;
    for (std::size_t s = 0; s < shards.size(); ++s) {
      same(shards[s].size() == out.size(), s, "knob_sweep", "swept other knobs than shard 0");
      const KnobRow& r = shards[s][k];
      same(r.knob == row.knob && r.value == row.value && r.method == row.method, s, what, "is another row in this shard");
      same(r.pvs == row.pvs, s, what, "gave other PVS sizes than in shard 0");
      row.misses += r.misses;
    }
    for (const Entry& e : interleave(shards.size(), [&](std::size_t s) -> const auto& { return shards[s][k].checked_frames; })) {
      const KnobRow& r = shards[e.shard][k];
      row.checked_frames.push_back(e.frame);
      take(row.checked_pvs, r.checked_pvs, e.index, e.shard, what);
      take(row.witnessed, r.witnessed, e.index, e.shard, what);
    }
  }
  return out;
}

}  // namespace cullcheck
