// A plugin registering an integrator name that is already taken: CLASH_NAME (a built-in's,
// or the example plugin's).
#include "integrators/cd_lagrange.hpp"
#include "integrators/registry.hpp"

NSBENCH_INTEGRATOR({CLASH_NAME, "clashes", &nsb::CdLagrange::parameters_spec,
                    &nsb::make_from_params<nsb::Integrator, nsb::CdLagrange>, false});
