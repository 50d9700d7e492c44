// Engine knobs drawn by the properties (MethodOptions, engine/method.hpp): a method must hold
// its claims at every setting it accepts, not only at the defaults.
//  - horizon bins: every power of two from 8 to 65,536 (coarse horizons round shadows inward
//    by up to a bin, fine ones stress the span arithmetic near kAngularSlack);
//  - quadtree leaf sizes 1 to 1000 (1: one building per leaf, deep trees; 1000: one leaf, no
//    cell culling at all);
//  - the guarded ΔH's motion budget (radius, height, turn), from tiny to generous, and whether
//    it certifies the next region ahead on a second thread (delta_prefetch).
// Shrinks towards the defaults. option_flags() gives the `cullcheck` flags that set them.
#pragma once

#include <rapidcheck.h>

#include <cstdint>
#include <sstream>
#include <string>
#include <tuple>

#include "engine/method.hpp"

namespace cullcheck {

inline rc::Gen<MethodOptions> method_options() {
  const auto bins = rc::gen::element<std::uint32_t>(4096, 8, 16, 32, 64, 128, 256, 512, 1024, 2048, 8192, 16384, 32768, 65536);
  const auto leaf = rc::gen::element<std::uint32_t>(8, 1, 2, 3, 4, 16, 32, 64, 1000);
  return rc::gen::map(rc::gen::tuple(bins, leaf, rc::gen::element(0.5, 0.05, 0.25, 1.0, 4.0), rc::gen::element(0.5, 0.05, 2.0),
                                     rc::gen::element(0.05, 0.01, 0.2, 0.6), rc::gen::element(true, false)),
                      [](const std::tuple<std::uint32_t, std::uint32_t, double, double, double, bool>& t) {
                        MethodOptions o;
                        std::tie(o.horizon_bins, o.quadtree_leaf_size, o.delta_radius, o.delta_height, o.delta_turn, o.delta_prefetch) = t;
                        return o;
                      });
}

inline std::string option_flags(const MethodOptions& o) {
  std::ostringstream s;
  s << "--horizon-bins " << o.horizon_bins << " --leaf-size " << o.quadtree_leaf_size << " --delta-radius " << o.delta_radius
    << " --delta-height " << o.delta_height << " --delta-turn " << o.delta_turn;
  if (!o.delta_prefetch) s << " --delta-no-prefetch";
  return s.str();
}

inline void showValue(const MethodOptions& o, std::ostream& os) { os << option_flags(o); }

}  // namespace cullcheck
