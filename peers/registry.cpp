// Peers: other codes' implementations of the schemes, wrapped as nsbench integrators
// (DESIGN.md section 2, "Peers run side by side"). Each is optional (a CMake option).
#include "core/registry.hpp"
#include "integrators/registry.hpp"
#ifdef NSBENCH_HAVE_SICONOS
#include "peers/siconos/siconos_integrator.hpp"
#endif

namespace nsb {

std::vector<IntegratorEntry> peer_integrators() {
  return {
#ifdef NSBENCH_HAVE_SICONOS
      {"siconos-moreau-jean", "peer: Siconos MoreauJeanOSI(theta), TimeStepping, Lemke LCP (linear problems)", &SiconosPeer<siconos::Scheme::MoreauJean>::parameters_spec, &make_from_params<Integrator, SiconosPeer<siconos::Scheme::MoreauJean>>, false, true},
      {"siconos-schatzman-paoli", "peer: Siconos SchatzmanPaoliOSI(theta), TimeStepping, position-level Lemke LCP (linear problems)", &SiconosPeer<siconos::Scheme::SchatzmanPaoli>::parameters_spec, &make_from_params<Integrator, SiconosPeer<siconos::Scheme::SchatzmanPaoli>>, false, true},
      {"siconos-d1-minus-linear", "peer: Siconos D1MinusLinearOSI, TimeSteppingD1Minus, impact and contact-force Lemke LCPs (linear problems)", &SiconosPeer<siconos::Scheme::D1MinusLinear>::parameters_spec, &make_from_params<Integrator, SiconosPeer<siconos::Scheme::D1MinusLinear>>, false, true},
#endif
  };
}

std::string peer_versions() {
#ifdef NSBENCH_HAVE_SICONOS
  return "Siconos kernel " + siconos_version();
#else
  return "none";
#endif
}

}  // namespace nsb
