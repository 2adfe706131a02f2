#pragma once
// For the tests that run every registered integrator on one problem.
#include <memory>
#include <string>

#include "core/parameters.hpp"
#include "integrators/registry.hpp"
#include "problems/problem.hpp"

namespace nsb::testing {

// The integrator of `entry` with its defaults, initialised on the problem's initial state;
// null when it declines the problem (InputError at init: a mass model, a nonlinearity).
inline std::unique_ptr<Integrator> init_or_decline(const IntegratorEntry& entry, const Problem& problem) {
  auto integrator = entry.make(Params(entry.parameters()));
  try {
    integrator->init(problem, problem.initial_state());
  } catch (const InputError&) {
    return nullptr;
  }
  return integrator;
}

// The physics-engine peers (peers/engine_scene.hpp) keep their own contact models (MuJoCo's
// soft contact, Bullet's sequential impulses, ODE's bounce with ERP/CFM): their restitution
// and friction are their own, which tests/peers/engines_test.cpp bounds and the studies
// measure, not the exact laws the generic tests hold the schemes to.
inline bool is_engine_peer(const std::string& name) { return name == "mujoco" || name == "bullet" || name == "ode"; }

}  // namespace nsb::testing
