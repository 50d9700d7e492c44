// RapidCheck generators aimed at the cases culling methods get wrong (issue "Trust the gate"):
// sub-metre gaps between buildings, eyes within a metre of a wall, large pitch and roll at street
// level, eyes aimed into the city rather than anywhere, and large occluded Manhattan grids.
// The properties count how often their cases reach each of these (properties/case_coverage.hpp)
// and assert floors, so a change that stops reaching them fails a test instead of going unseen.
//
// Like rapidcheck_gens.hpp, scenes are SceneSpecs rebuilt by make_city (one replay command per
// case), and every draw shrinks: building indices towards 0, offsets towards the smallest.
//
// Link target: cullcheck_generators_rc (bodies in rapidcheck_hard_cases.cpp).
#pragma once

#include <rapidcheck.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <tuple>

#include "generators/rapidcheck_gens.hpp"

namespace cullcheck::generators::rcgen {

// --- Scenes with gaps narrower than 1 m ---------------------------------------------------------

// Manhattan blocks whose buildings nearly fill their lots: setback 2-500 mm and width jitter
// 0-5%, so neighbouring buildings of a block stand 4 mm to about 1 m apart (2 x setback plus
// the jitter); 1-4 x 1-4 blocks of 2-6 lots, 20-60 m blocks, 6-16 m streets, up to 30% slabs.
rc::Gen<SceneSpec> narrow_gap_manhattan_spec();

// Rotated rectangles packed closely: 4-20 in a 50-150 m square, at least 0.1-1 m apart.
rc::Gen<SceneSpec> narrow_gap_scatter_spec();

// Long slabs and blocks of every height packed closely (0.3-3 m apart): 8-25 rotated rectangles
// in a 50-120 m square, up to 40 m long, 30-70% thin, 1-40 m tall. Low buildings stand in front
// of the long facades of tall ones, which an eye looking along the facade sees obliquely (the
// occlusion horizon's merge delay, properties/grazing_horizon_cases.hpp).
rc::Gen<SceneSpec> facade_scatter_spec();

// Small buildings (2-12 m) spread apart in a 40-160 m square, 3-30 m tall, up to half of them
// thin: a building near the eye is small enough that its shadow enters the horizon before the
// buildings behind it are tested (the near-plane guard, properties/grazing_horizon_cases.hpp).
rc::Gen<SceneSpec> small_building_scatter_spec();

// The scenes of the hard-case properties: the large occluded Manhattan grids (most of the city
// hidden from the street), the narrow-gap cities, and the small scenes of every generator.
rc::Gen<SceneSpec> hard_scene_spec();

// --- Cameras ------------------------------------------------------------------------------------

// `cameras`, turned to look at a drawn building (yaw at its centre, off by up to ±20 degrees;
// from above the roofs, pitched down at it too), so the view runs into the city instead of out
// of it. Omnidirectional cameras are left as they are.
rc::Gen<Camera> aimed_into_the_city(const Scene& scene, rc::Gen<Camera> cameras);

// An eye 1 cm to 1 m out from a drawn wall (outward along the wall's normal, 1.5-2 m up), looking
// along the wall, away from it, at it (the near plane may then lie beyond the wall: clipped
// geometry hides nothing) or anywhere. Falls back to the nearest open point when the spot lies
// in another building.
rc::Gen<Camera> wall_camera(const Scene& scene);

// `cameras` pitched or rolled hard: pitch 30-90 degrees up or down, or roll 30-180 degrees
// either way, or both (the 6-DoF cases of thesis ch. 3.1.2 at street level, where occluders are
// near and the horizon is high).
rc::Gen<Camera> steep(rc::Gen<Camera> cameras);

// The cameras of the hard-case properties: street level aimed into the city (most), hugging a
// wall, pitched or rolled hard at street level, anywhere at street level, above the roofs aimed
// down into the city.
rc::Gen<Camera> hard_camera(const Scene& scene);

// A hard scene and a hard camera in it; shrinks the scene first, then the camera.
rc::Gen<SceneCase> hard_scene_case(rc::Gen<SceneSpec> specs = hard_scene_spec());

// --- Alleys: narrow gaps that run through a whole block ---------------------------------------

// Manhattan blocks of 2-3 lots in one row, so the 4 mm to 20 cm gaps between neighbours (2 x
// setback, no jitter) run straight through the block, 30-60 m deep, beside narrow 6-8 m streets:
// from across the street, what stands beyond the block shows only down an alley, from a stretch
// of the street about as wide as the alley (the case view-cell boundary sampling must not leave
// uncovered). 2-4 x 2-4 blocks, no slabs.
rc::Gen<SceneSpec> alley_manhattan_spec();

}  // namespace cullcheck::generators::rcgen
