#pragma once
// For the tests that run every registered integrator on one problem.
#include <string>

#include "check/conformance.hpp"

namespace nsb::testing {

// The integrator with its defaults initialised on the problem, or null when it declines it.
using nsb::init_or_decline;

// The physics-engine peers (peers/engine_scene.hpp) keep their own contact models (MuJoCo's
// soft contact, Bullet's sequential impulses, ODE's bounce with ERP/CFM): their restitution
// and friction are their own, which tests/peers/engines_test.cpp bounds and the studies
// measure, not the exact laws the generic tests hold the schemes to.
inline bool is_engine_peer(const std::string& name) { return name == "mujoco" || name == "bullet" || name == "ode"; }

}  // namespace nsb::testing
