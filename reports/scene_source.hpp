// Where a run's scene comes from: a named generator with seed and parameters, or a scene file.
// It rebuilds the scene and prints the command-line flags that rebuild it, which every replay
// line carries.
#pragma once

#include <cstdint>
#include <string>

#include "core/scene.hpp"

namespace cullcheck {

struct SceneSource {
  std::string generator = "default";
  std::uint64_t seed = 1;
  std::string parameters_json = "{}";  // overlaid on the generator's defaults
  std::string file;                    // when set, the scene is read from this file instead

  Scene load() const;
  // e.g. "--generator plaza --seed 7 --params '{\"blocks_x\":2}'" or "--scene city.json"
  std::string replay_flags() const;
};

// Quotes a string for a POSIX shell command line.
std::string shell_quote(const std::string& text);
// A number as command-line text that reads back to the same double (17 significant digits):
// replays of tiny or odd radii (1e-9 m) must not round to 0.000000.
std::string round_trip_text(double value);

}  // namespace cullcheck
