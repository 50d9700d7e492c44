// Range checks for generator parameters, raising InputError(object, field, "<owner>: ...").
#pragma once

#include <sstream>
#include <string>

#include "core/errors.hpp"

namespace cullcheck::generators {

class ParamChecks {
 public:
  ParamChecks(std::string object, std::string owner) : object_(std::move(object)), owner_(std::move(owner)) {}

  [[noreturn]] void fail(const std::string& field, const std::string& problem) const {
    throw InputError(object_, field, owner_ + ": " + problem);
  }

  // Closed range [lo, hi]; NaN fails.
  template <class T>
  void in_range(const std::string& field, T value, T lo, T hi) const {
    if (!(value >= lo && value <= hi))
      fail(field, "must lie in [" + text(lo) + ", " + text(hi) + "] (got " + text(value) + ")");
  }
  // Open at the bottom: (lo, hi].
  void above(const std::string& field, double value, double lo, double hi) const {
    if (!(value > lo && value <= hi))
      fail(field, "must lie in (" + text(lo) + ", " + text(hi) + "] (got " + text(value) + ")");
  }
  template <class T>
  void not_below(const std::string& field, T value, const std::string& other, T other_value) const {
    if (!(value >= other_value))
      fail(field, "must be >= " + other + " (" + text(other_value) + "; got " + text(value) + ")");
  }

  template <class T>
  static std::string text(T v) {
    std::ostringstream s;
    s << v;
    return s.str();
  }

 private:
  std::string object_;
  std::string owner_;
};

}  // namespace cullcheck::generators
