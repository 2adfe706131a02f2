#pragma once
// For the tests that run every registered integrator on one problem.
#include <memory>

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

}  // namespace nsb::testing
