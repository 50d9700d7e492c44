// main() for the property tests: fixes RapidCheck's seed and budget unless RC_PARAMS is given,
// so CI runs are reproducible, and scales the budget with CULLCHECK_RC_BUDGET (e.g. 20 for a
// long fuzzing run; the default is 500 cases per property). On a failure RapidCheck prints RC_PARAMS="reproduce=..."; together with
// the test binary and --gtest_filter that is the one-line replay, which we print as well.
#include <gtest/gtest.h>

#include <cstdlib>
#include <iostream>
#include <string>

namespace {

class ReplayPrinter : public testing::EmptyTestEventListener {
 public:
  explicit ReplayPrinter(std::string binary) : binary_(std::move(binary)) {}
  void OnTestEnd(const testing::TestInfo& info) override {
    if (!info.result()->Failed()) return;
    std::cerr << "replay: RC_PARAMS=\"" << params() << "\" " << binary_ << " --gtest_filter=" << info.test_suite_name()
              << "." << info.name() << "   (RapidCheck's reproduce= line above, if any, replays the exact case)\n";
  }
  static std::string params() {
    const char* p = std::getenv("RC_PARAMS");
    return p ? p : "";
  }

 private:
  std::string binary_;
};

}  // namespace

int main(int argc, char** argv) {
  if (std::getenv("RC_PARAMS") == nullptr) {
    long budget = 1;
    if (const char* b = std::getenv("CULLCHECK_RC_BUDGET")) budget = std::max(1L, std::strtol(b, nullptr, 10));
    const std::string params = "seed=20261125 max_success=" + std::to_string(500 * budget) + " max_size=100";
    setenv("RC_PARAMS", params.c_str(), 1);
  }
  testing::InitGoogleTest(&argc, argv);
  testing::UnitTest::GetInstance()->listeners().Append(new ReplayPrinter(argv[0]));
  return RUN_ALL_TESTS();
}
