// Wall time since a moment, for the timings the reports print (never for a decision: those
// must not depend on the machine).
#pragma once

#include <chrono>

namespace cullcheck {

inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

inline double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace cullcheck
