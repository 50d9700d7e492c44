#include "oracle/sampling.hpp"

#include <cmath>
#include <nlohmann/json.hpp>

#include "core/errors.hpp"

namespace cullcheck::oracle {

void validate(const SamplingOptions& o) {
  const std::string object = "sampling options";
  if (!(std::isfinite(o.spacing_m) && o.spacing_m > 0)) throw InputError(object, "spacing_m", "must be finite and > 0");
  if (o.face_grid < 1) throw InputError(object, "face_grid", "must be >= 1");
  if (o.edge_samples < 1) throw InputError(object, "edge_samples", "must be >= 1");
  if (!(o.inset >= 0 && o.inset < 0.5)) throw InputError(object, "inset", "must lie in [0, 0.5)");
  if (!(o.graze_offset >= 0 && o.graze_offset <= 0.1)) throw InputError(object, "graze_offset", "must lie in [0, 0.1]");
  if (o.max_samples_per_building < 1) throw InputError(object, "max_samples_per_building", "must be >= 1");
  if (o.frustum_resolution < 0 || o.frustum_resolution > 65536)
    throw InputError(object, "frustum_resolution", "must lie in [0, 65536]");
  if (o.threads < 1 || o.threads > 1024) throw InputError(object, "threads", "must lie in [1, 1024]");
}

void to_json(nlohmann::json& j, const SamplingOptions& o) {
  j = {{"spacing_m", o.spacing_m},
       {"face_grid", o.face_grid},
       {"edge_samples", o.edge_samples},
       {"inset", o.inset},
       {"max_samples_per_building", o.max_samples_per_building},
       {"graze_offset", o.graze_offset},
       {"frustum_resolution", o.frustum_resolution},
       {"stop_when_witnessed", o.stop_when_witnessed},
       {"seed", o.seed}};  // not threads: the answers do not depend on them (reports stay the same on any machine)
}

void from_json(const nlohmann::json& j, SamplingOptions& o) {
  SamplingOptions d;
  o.spacing_m = j.value("spacing_m", d.spacing_m);
  o.face_grid = j.value("face_grid", d.face_grid);
  o.edge_samples = j.value("edge_samples", d.edge_samples);
  o.inset = j.value("inset", d.inset);
  o.max_samples_per_building = j.value("max_samples_per_building", d.max_samples_per_building);
  o.graze_offset = j.value("graze_offset", d.graze_offset);
  o.frustum_resolution = j.value("frustum_resolution", d.frustum_resolution);
  o.stop_when_witnessed = j.value("stop_when_witnessed", false);  // reports written before it was an option cast every ray
  o.seed = j.value("seed", d.seed);
  o.threads = j.value("threads", d.threads);
}

}  // namespace cullcheck::oracle
