// Typed errors for bad input (design: "Bad input"). Library code throws these; the CLI prints
// what() as one line and exits non-zero.
#pragma once

#include <stdexcept>
#include <string>

namespace cullcheck {

// A scene, camera or path that cannot be used, naming the object and the field at fault.
class InputError : public std::runtime_error {
 public:
  InputError(std::string object, std::string field, const std::string& problem)
      : std::runtime_error(object + ": field '" + field + "': " + problem),
        object_(std::move(object)),
        field_(std::move(field)),
        problem_(problem) {}
  const std::string& object() const { return object_; }
  const std::string& field() const { return field_; }
  const std::string& problem() const { return problem_; }
  // The same error with `where` (e.g. a file name) put before the object's name.
  InputError located(const std::string& where) const { return {where + ": " + object_, field_, problem_}; }

 private:
  std::string object_;
  std::string field_;
  std::string problem_;
};

}  // namespace cullcheck
