// A method held to conservativeness whatever it claims (`--hold-conservative` on gate, verify
// and fuzz): how a paper's claim the engine does not gate is checked, e.g. that range detection
// as published (rdt) drops only what lies outside the frustum. Everything else is forwarded.
#pragma once

#include <memory>

#include "engine/method.hpp"

namespace cullcheck {

std::unique_ptr<CullingMethod> held_conservative(std::unique_ptr<CullingMethod> method);

}  // namespace cullcheck
