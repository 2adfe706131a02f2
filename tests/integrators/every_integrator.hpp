#pragma once
// For the tests that run every registered integrator on one problem.
#include "integrators/conformance.hpp"

namespace nsb::testing {

// The integrator with its defaults initialised on the problem, or null when it declines it.
using nsb::init_or_decline;

}  // namespace nsb::testing
