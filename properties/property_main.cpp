// main() for the property tests: fixes RapidCheck's seed and budget unless RC_PARAMS is given,
// so CI runs are reproducible, and scales the budget with CULLCHECK_RC_BUDGET (e.g. 20 for a
// long fuzzing run; the default is 500 cases per property). On a failure RapidCheck prints RC_PARAMS="reproduce=..."; together with
// the test binary and --gtest_filter that is the one-line replay, which we print as well.
//
// Seeds: CI runs the fixed seed 20261125. Nightly runs rotate it: CULLCHECK_SEED=date takes the
// UTC date as YYYYMMDD (a new seed each day, the same all day on every machine), CULLCHECK_SEED=N
// takes N. The seed in use is printed first as the line that replays the whole run.
#include <gtest/gtest.h>

#include <cerrno>
#include <cstdint>
#include <cmath>
#include <cstdlib>
#include <ctime>
#include <iostream>
#include <string>

namespace {

constexpr std::uint64_t kCiSeed = 20261125;

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

// The seed CULLCHECK_SEED names: unset or empty for the CI seed, "date" for today's UTC date as
// YYYYMMDD, else a decimal number. Anything else is refused (exit 2) rather than guessed at.
std::uint64_t run_seed() {
  const char* s = std::getenv("CULLCHECK_SEED");
  if (s == nullptr || *s == '\0') return kCiSeed;
  const std::string text = s;
  if (text == "date") {
    const std::time_t now = std::time(nullptr);
    std::tm utc{};
    gmtime_r(&now, &utc);
    return static_cast<std::uint64_t>((utc.tm_year + 1900) * 10000 + (utc.tm_mon + 1) * 100 + utc.tm_mday);
  }
  char* end = nullptr;
  errno = 0;
  const unsigned long long n = std::strtoull(text.c_str(), &end, 10);
  if (errno != 0 || end == text.c_str() || *end != '\0' || text.front() == '-') {
    std::cerr << "CULLCHECK_SEED='" << text << "' is neither 'date' nor a non-negative decimal number\n";
    std::exit(2);
  }
  return n;
}

}  // namespace

int main(int argc, char** argv) {
  if (std::getenv("RC_PARAMS") == nullptr) {
    // A fraction below 1 (e.g. 0.5: the sanitizer run, ci/test.sh) runs fewer cases, at least 1.
    double budget = 1.0;
    if (const char* b = std::getenv("CULLCHECK_RC_BUDGET")) {
      char* end = nullptr;
      budget = std::strtod(b, &end);
      if (end == b || *end != '\0' || !(budget > 0.0) || !(budget <= 1e6)) {
        std::cerr << "CULLCHECK_RC_BUDGET='" << b << "' is not a positive number\n";
        return 2;
      }
    }
    const long max_success = std::max(1L, std::lround(500.0 * budget));
    const std::uint64_t seed = run_seed();
    const std::string params = "seed=" + std::to_string(seed) + " max_success=" + std::to_string(max_success) + " max_size=100";
    setenv("RC_PARAMS", params.c_str(), 1);
    std::cout << "replay: RC_PARAMS=\"" << params << "\" " << argv[0]
              << (seed == kCiSeed ? "   (the fixed CI seed)\n" : "   (rotated by CULLCHECK_SEED)\n");
  }
  testing::InitGoogleTest(&argc, argv);
  testing::UnitTest::GetInstance()->listeners().Append(new ReplayPrinter(argv[0]));
  return RUN_ALL_TESTS();
}
