#!/usr/bin/env bash
# Installs cullcheck from a build tree into a temporary prefix, then configures, builds and runs
# the separate user project examples/installed_project against it (find_package(cullcheck),
# cullcheck::oracle, <cullcheck/gate.hpp> from GoogleTest). Run by CTest as `installed_package`.
# Usage: test_installed_package.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1
source_dir=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmake --install "$build" --prefix "$work/prefix" >"$work/install.log"
[ -f "$work/prefix/lib/cmake/cullcheck/cullcheckConfig.cmake" ] || { echo "no package config installed"; exit 1; }
[ -x "$work/prefix/bin/cullcheck" ] || { echo "the cullcheck program was not installed"; exit 1; }
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
# The consumer is compiled as the library was (a sanitizer build's archives need the sanitizers'
# flags and runtime at link time).
cache_value() { sed -n "s/^$1:[A-Z]*=//p" "$build/CMakeCache.txt"; }
cmake -S "$source_dir/examples/installed_project" -B "$work/consumer" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_CXX_COMPILER="$(cache_value CMAKE_CXX_COMPILER)" -DCMAKE_CXX_FLAGS="$(cache_value CMAKE_CXX_FLAGS)" \
  -DCMAKE_PREFIX_PATH="$work/prefix" >"$work/configure.log" || { cat "$work/configure.log"; exit 1; }
cmake --build "$work/consumer" >"$work/build.log" 2>&1 || { cat "$work/build.log"; exit 1; }
"$work/consumer/my_culler_test"
echo "installed package: find_package(cullcheck) and cullcheck::oracle work from $work/prefix"
