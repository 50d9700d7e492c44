#!/usr/bin/env bash
# Installs cullcheck's build dependencies from Debian packages. Idempotent: skips apt
# when every package is already installed.
set -euo pipefail
packages=(
  build-essential cmake ninja-build pkg-config
  libcgal-dev libgmp-dev libmpfr-dev libboost-dev
  libembree-dev libtbb-dev
  librapidcheck-dev libbenchmark-dev libgtest-dev libgmock-dev
  nlohmann-json3-dev libcli11-dev libspng-dev
  python3
  libtinygltf-dev libtinyobjloader-dev libassimp-dev
  libproj-dev proj-data  # footprint files' CRSs (core/formats/crs_projection.cpp)
  libgdal-dev  # elevation models: GeoTIFF, ESRI ASCII grids (core/formats/dem_reader.cpp)
  chromium  # the report page's browser test (reports/html/tests/browser_test.sh) and screenshot
  clang-14 libclang-rt-14-dev llvm-14  # the sanitize preset: ASan, UBSan, libFuzzer, llvm-symbolizer
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi
echo "install-deps: installing ${missing[*]}"
SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
