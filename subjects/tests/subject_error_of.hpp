// The SubjectError a call throws, for tests of the subject readers' error paths.
#pragma once

#include <gtest/gtest.h>

#include "subjects/subject_error.hpp"

namespace cullcheck::test_support {

// The SubjectError thrown by `f`; a test failure (and a placeholder error) when it throws none.
template <class F>
SubjectError error_of(F&& f) {
  try {
    f();
  } catch (const SubjectError& e) {
    return e;
  }
  ADD_FAILURE() << "no SubjectError thrown";
  return SubjectError(SubjectError::Kind::protocol, "(none)", 0, "(none)");
}

}  // namespace cullcheck::test_support
