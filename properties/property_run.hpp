// Runs a RapidCheck property from inside a GoogleTest test, like rc::check, but with its own
// number of cases and, when asked, without shrinking; so a test can count over the property's
// cases (properties/case_coverage.hpp) and assert on the counts afterwards, or expect a
// deliberately broken method to fail the property (a test that a property can fail).
//
// The number of cases scales with the run's budget: `cases` at the default budget (RC_PARAMS
// max_success=500, which property_main.cpp sets), so CULLCHECK_RC_BUDGET=20 runs 20 times as
// many. The seed is the run's (property_main.cpp: fixed for CI, rotating with CULLCHECK_SEED)
// mixed with `id`;
// RC_PARAMS="reproduce=..." replays a failure of the property named `id` and skips the others.
#pragma once

#include <rapidcheck.h>
#include <rapidcheck/detail/TestListenerAdapter.h>

#include <algorithm>
#include <cstdint>
#include <iostream>
#include <string>
#include <unordered_map>
#include <utility>

namespace cullcheck {

// The run's seed mixed with the property's id (FNV-1a, the same on every platform), so that
// properties run on different cases rather than each on the same first ones.
inline std::uint64_t property_seed(std::uint64_t run_seed, const std::string& id) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (unsigned char ch : id) h = (h ^ ch) * 0x100000001b3ULL;
  return run_seed ^ h;
}

// `cases` scaled by the run's budget (max_success / 500), at least 1.
inline int scaled_cases(int cases) {
  const int max_success = rc::detail::configuration().testParams.maxSuccess;
  return std::max(1, static_cast<int>(static_cast<long long>(cases) * max_success / 500));
}

// True when RC_PARAMS asks to reproduce failures: every property not named there runs no case.
inline bool reproducing() { return !rc::detail::configuration().reproduce.empty(); }

struct PropertyOutcome {
  bool held = false;
  int cases = 0;  // successful cases run
};

// Checks `property` as `id` with `params`, printing its outcome; with `expect_failure` a failure
// is not reported to RapidCheck's exit summary (whose "Some of your RapidCheck properties had
// failures" would read as a failure of the run), and `reproduce`, when given, is the map of
// failures to replay (rc::check's; RapidCheck's default without it).
template <class Property>
rc::detail::TestResult check_printed(const std::string& id, const rc::detail::TestParams& params, Property&& property,
                                     bool expect_failure,
                                     const std::unordered_map<std::string, rc::detail::Reproduce>* reproduce = nullptr) {
  using namespace rc::detail;
  TestMetadata metadata;
  metadata.id = id;
  metadata.description = id;
  std::cerr << "\n- " << id << (expect_failure ? " (expected to fail)" : "") << "\n";
  TestListenerAdapter silent;
  // One branch runs, so `property` is forwarded once.
  const TestResult result =
      !expect_failure ? checkProperty(toProperty(std::forward<Property>(property)), metadata, params)
      : reproduce     ? checkProperty(toProperty(std::forward<Property>(property)), metadata, params, silent, *reproduce)
                      : checkProperty(toProperty(std::forward<Property>(property)), metadata, params, silent);
  printResultMessage(result, std::cerr);
  std::cerr << "\n";
  return result;
}

// With `expect_failure`, a failure is not reported to RapidCheck's exit summary (whose
// "reproduce" line would read as a real failure); the failing case is still printed.
template <class Property>
PropertyOutcome run_property(const std::string& id, int cases, bool shrink, Property&& property, bool expect_failure = false) {
  using namespace rc::detail;
  TestParams params = configuration().testParams;
  params.maxSuccess = scaled_cases(cases);
  params.seed = property_seed(params.seed, id);
  params.disableShrinking = params.disableShrinking || !shrink;
  const rc::detail::TestResult result = check_printed(id, params, std::forward<Property>(property), expect_failure);
  PropertyOutcome out;
  out.held = result.template is<SuccessResult>();
  if (out.held) out.cases = result.template get<SuccessResult>().numSuccess;
  return out;
}

// rc::check for a property a test expects to fail (a method the oracle refutes, a search that
// must find that): the same cases as rc::check (the run's parameters, seed and reproduce
// entries), the failing case printed, but not reported to RapidCheck's exit summary, whose
// "Some of your RapidCheck properties had failures" would read as a failure of the run. True
// when the property held.
template <class Testable>
bool check_expecting_failure(const std::string& description, Testable&& testable) {
  const rc::detail::Configuration& config = rc::detail::configuration();
  return check_printed(description, config.testParams, std::forward<Testable>(testable), true, &config.reproduce)
      .template is<rc::detail::SuccessResult>();
}

}  // namespace cullcheck
