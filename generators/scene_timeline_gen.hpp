// Seeded scene timelines (core/camera_path.hpp: SceneEvent) for dynamic-scene walks (Wang et
// al. 2001, section 6: objects inserted and deleted while the viewer moves). Every `every`
// frames one event: the objects that vanished at the previous event come back, and a fresh
// `churn` share of the present objects vanishes; a `late` share of the objects is absent at
// frame 0 and appears at the first event. A pure function of its parameters and seed, like the
// paths; it asks for a path's "timeline" parameter (camera_path_registry.cpp), so a replay
// command carries it.
#pragma once

#include <cstdint>
#include <vector>

#include "core/camera_path.hpp"
#include "core/scene.hpp"

namespace cullcheck::generators {

struct TimelineParams {
  int every = 30;        // frames between events (>= 1)
  double churn = 0.01;   // share of the present objects vanishing at each event, at least one
  double late = 0.0;     // share of the objects absent at frame 0, appearing at the first event

  template <class Self, class Visitor>
  static void visit(Self& s, Visitor&& v) {
    v("every", s.every), v("churn", s.churn), v("late", s.late);
  }
};

// Throws InputError naming the "timeline" field out of range.
std::vector<SceneEvent> scene_timeline(const Scene& scene, std::size_t frames, const TimelineParams& params, std::uint64_t seed);

}  // namespace cullcheck::generators
