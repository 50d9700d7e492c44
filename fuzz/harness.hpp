// What every libFuzzer harness shares (fuzz/README in fuzz/CMakeLists.txt).
//
// A reader may accept an input or reject it with its typed error (core/errors.hpp InputError for
// scene, camera, path and mesh files; subjects/subject_error.hpp SubjectError for what a subject
// sends). Anything else escaping a reader - another exception type, a crash, a sanitizer report
// - is a bug: `reject_only_as<E>` turns a foreign exception into abort(), which libFuzzer records
// as a crash with the input that caused it. An accepted result is then checked for the
// invariants every later stage relies on without re-checking (`require`): a reader that accepts
// garbage is as wrong as one that crashes on it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <typeinfo>
#include <unistd.h>

namespace cullcheck::fuzz {

[[noreturn]] inline void crash(const std::string& why) {
  std::fprintf(stderr, "fuzz harness: %s\n", why.c_str());
  std::fflush(stderr);
  std::abort();
}

// An invariant of an accepted input: its failure is a crash, like a foreign exception.
inline void require(bool ok, const std::string& what) {
  if (!ok) crash("accepted input breaks an invariant: " + what);
}

// Runs `read` on the input; E is the one exception type a rejection may take.
template <class E, class Read>
void reject_only_as(Read&& read) {
  try {
    read();
  } catch (const E&) {
    // A typed rejection: the answer the reader owes bad input.
  } catch (const std::exception& e) {
    crash(std::string("a reader threw something other than its typed error: ") + typeid(e).name() + ": " + e.what());
  } catch (...) {
    crash("a reader threw a non-std::exception");
  }
}

inline std::string bytes_of(const std::uint8_t* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

// The readers of files take a path: the input goes to one scratch file per process (per name),
// in $TMPDIR, overwritten on every execution and removed at exit.
inline std::string scratch_file(const std::string& name, const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path dir = [] {
    static std::filesystem::path d = std::filesystem::temp_directory_path() / ("cullcheck_fuzz_" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    std::atexit([] {
      std::error_code ignored;
      std::filesystem::remove_all(d, ignored);
    });
    return d;
  }();
  const std::string path = (dir / name).string();
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  out.close();
  if (!out) crash("cannot write the scratch file " + path);
  return path;
}

}  // namespace cullcheck::fuzz
