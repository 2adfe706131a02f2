// Peers: other codes' implementations of the schemes, wrapped as nsbench integrators
// (docs/method.md section 2, "Peers run side by side"). Each is optional (a CMake option) and
// registers itself (NSBENCH_INTEGRATOR in its .cpp, with peer = true).
#include "integrators/registry.hpp"
#ifdef NSBENCH_HAVE_SICONOS
#include "peers/siconos/siconos_integrator.hpp"  // siconos_version()
#endif

namespace nsb {

std::string peer_versions() {
#ifdef NSBENCH_HAVE_SICONOS
  return "Siconos kernel " + siconos_version();
#else
  return "none";
#endif
}

}  // namespace nsb
