// A plugin registering an integrator name that is already taken: CLASH_NAME (a built-in's,
// or the example plugin's), after a companion of a free name, CLASH_NAME "-companion", which
// the refused plugin must not leave registered (all its entries or none).
#include "integrators/cd_lagrange.hpp"
#include "integrators/registry.hpp"

NSBENCH_INTEGRATOR({CLASH_NAME "-companion", "registered before the clash", &nsb::CdLagrange::parameters_spec,
                    &nsb::make_from_params<nsb::Integrator, nsb::CdLagrange>, false});
NSBENCH_INTEGRATOR({CLASH_NAME, "clashes", &nsb::CdLagrange::parameters_spec,
                    &nsb::make_from_params<nsb::Integrator, nsb::CdLagrange>, false});
