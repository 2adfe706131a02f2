#pragma once
// Whether a physics-engine peer (mujoco, bullet, ode) is built here: each is built where its
// package is found, so a test of one skips it with a warning when it is not.
#include <catch2/catch.hpp>

#include <string>

#include "integrators/registry.hpp"

namespace nsb::test {

inline bool engine_built(const std::string& name) {
  for (const auto& e : nsb::integrator_registry())
    if (e.name == name) return true;
  WARN(name << " is not built here (its package was not found, or NSBENCH_ENGINES=OFF): skipped");
  return false;
}

}  // namespace nsb::test
