// The generators' random numbers: core/random.hpp (shared with the VbAoI simulation).
#pragma once

#include "core/random.hpp"

namespace cullcheck::generators {
using cullcheck::Random;
using cullcheck::splitmix64;
}  // namespace cullcheck::generators
