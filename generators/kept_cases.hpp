// Kept counterexamples (design: "keep the counterexample as a regression test"): small hand-built
// scenes on which the oracle refuted a published rule, reachable like any city so that their
// replays are one self-contained command: `--generator kept --params '{"case":"low_planter"}'`.
// Each comes with the region query that fails on it (a disc centre, ε, and the viewpoint that
// sees what the published method culls), for the properties and the claims ledger.
#pragma once

#include <string>
#include <vector>

#include "core/camera.hpp"
#include "core/scene.hpp"

namespace cullcheck::generators {

struct KeptParams {
  std::string case_name = "low_planter";

  template <class Self, class Visitor>
  static void visit(Self& s, Visitor&& v) {
    v("case", s.case_name);
  }
};

const std::vector<std::string>& kept_case_names();
// Throws InputError naming the known cases.
void validate(const KeptParams& p, const std::string& generator = "kept");
Scene kept_city(const KeptParams& p);  // no randomness: the seed is ignored

struct KeptRegionQuery {
  Camera centre;
  double radius = 0.0;
  Camera from;           // sees `building`
  ObjectId building = 0;
  bool disc_in_open_ground = false;  // the disc crosses no building
};
KeptRegionQuery kept_region_query(const std::string& case_name);

}  // namespace cullcheck::generators
