// Conservativeness (design: "Properties"): for every method that claims it, the buildings the
// oracle sees are a subset of the PVS — over generated scenes (all generators, small), cameras
// at street level and above the rooftops, pitch and roll, narrow, ordinary and 360-degree fields
// of view, occluders below and above the eye. A failure logs the `cullcheck verify` command
// that replays it; RapidCheck shrinks it to a small city first.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include "engine/method.hpp"
#include "generators/rapidcheck_gens.hpp"
#include "oracle/oracle.hpp"
#include "properties/property_oracle.hpp"

namespace cullcheck {
namespace {

namespace rcgen = generators::rcgen;

void check_conservative(const std::string& method_name, const generators::SceneCase& c) {
  const Scene scene = generators::scene_of(c.spec);
  RC_PRE(!scene.buildings.empty());
  auto method = make_method(method_name, scene);
  RC_ASSERT(method->claims_conservative());
  const oracle::Oracle truth(scene);
  const oracle::OracleAnswer seen = truth.visible_set(c.camera, property_oracle());
  const CullResult culled = method->cull(c.camera);
  std::vector<ObjectId> missed;
  std::set_difference(seen.visible.begin(), seen.visible.end(), culled.pvs.begin(), culled.pvs.end(),
                      std::back_inserter(missed));
  if (!missed.empty()) {
    RC_LOG() << "replay: cullcheck verify " << c << " --method " << method_name << "\n";
    RC_LOG() << "building " << missed.front() << " seen by the oracle (" << seen.model << ")";
    if (seen.sampling) RC_LOG() << ": " << oracle::describe(seen.sampling->witnesses.at(missed.front()));
    RC_LOG() << "\n";
  }
  RC_ASSERT(missed.empty());
}

RC_GTEST_PROP(Conservativeness, FrustumOnGeneratedScenes, ()) {
  check_conservative("frustum", *rcgen::scene_case());
}

RC_GTEST_PROP(Conservativeness, ObjectSpaceHorizonOnGeneratedScenes, ()) {
  check_conservative("oh_os_conservative", *rcgen::scene_case());
}

RC_GTEST_PROP(Conservativeness, ObjectSpaceHorizonWithOccludersBelowTheEye, ()) {
  check_conservative("oh_os_conservative", *rcgen::scene_case(rcgen::low_occluder_spec(1.7)));
}

RC_GTEST_PROP(Conservativeness, ObjectSpaceHorizonWithOccludersAboveTheEye, ()) {
  check_conservative("oh_os_conservative", *rcgen::scene_case(rcgen::tall_occluder_spec(1.7)));
}

// Near planes from 1 cm to 5 m: clipped geometry hides nothing, so what reaches in front of the
// near plane must not be used as an occluder.
RC_GTEST_PROP(Conservativeness, ObjectSpaceHorizonWithDeepNearPlanes, ()) {
  generators::SceneCase c = *rcgen::scene_case();
  c.camera.near = *rc::gen::element(0.01, 0.5, 2.0, 5.0);
  c.camera.far = std::max(c.camera.far, c.camera.near * 2);
  check_conservative("oh_os_conservative", c);
}

}  // namespace
}  // namespace cullcheck
