// The text of replay commands: every failure prints one `cullcheck ...` line that reproduces it
// (design: "Replay from a seed"), so its arguments must read back exactly.
#pragma once

#include <string>
#include <vector>

#include "core/camera.hpp"
#include "core/scene.hpp"

namespace cullcheck {

// Quotes a string for a POSIX shell command line.
std::string shell_quote(const std::string& text);
// A number as command-line text that reads back to the same double (17 significant digits):
// replays of tiny or odd radii (1e-9 m) must not round to 0.000000.
std::string round_trip_text(double value);
// A camera as one shell-quoted line of camera JSON, e.g. for `--camera`.
std::string camera_arg(const Camera& camera);
// Object ids as "[1,4,9]", for a failure's detail.
std::string ids_text(const std::vector<ObjectId>& ids);

}  // namespace cullcheck
