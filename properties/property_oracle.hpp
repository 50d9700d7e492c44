// The oracle's density for properties: coarser than the report's (cases are many), still dense
// enough that a culled visible building is very likely witnessed; one thread per case.
// Replays of property failures name the same density: --spacing 3 --frustum-resolution 128.
#pragma once

#include "oracle/oracle.hpp"

namespace cullcheck {

inline oracle::OracleOptions property_oracle() {
  oracle::OracleOptions o;
  o.sampling.spacing_m = 3.0;
  o.sampling.frustum_resolution = 128;
  o.sampling.threads = 1;
  return o;
}

}  // namespace cullcheck
