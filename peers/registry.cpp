// Peers: other codes' implementations of the schemes, wrapped as nsbench integrators
// (DESIGN.md section 2, "Peers run side by side"), and the physics engines on the rigid
// problems (peers/engine_scene.hpp). Each is optional (a CMake option, or its package found)
// and registers itself (NSBENCH_INTEGRATOR in its .cpp, with peer = true).
#include <string>
#include <vector>

#include <fmt/format.h>

#include "integrators/registry.hpp"
#ifdef NSBENCH_HAVE_SICONOS
#include "peers/siconos/siconos_integrator.hpp"  // siconos_version()
#endif
#ifdef NSBENCH_HAVE_MUJOCO
#include "peers/mujoco/mujoco_peer.hpp"  // mujoco_version()
#endif
#ifdef NSBENCH_HAVE_BULLET
#include "peers/bullet/bullet_peer.hpp"  // bullet_version()
#endif
#ifdef NSBENCH_HAVE_ODE
#include "peers/ode/ode_peer.hpp"  // ode_version()
#endif

namespace nsb {

std::string peer_versions() {
  std::vector<std::string> v;
#ifdef NSBENCH_HAVE_SICONOS
  v.push_back("Siconos kernel " + siconos_version());
#endif
#ifdef NSBENCH_HAVE_MUJOCO
  v.push_back("MuJoCo " + mujoco_version());
#endif
#ifdef NSBENCH_HAVE_BULLET
  v.push_back("Bullet " + bullet_version());
#endif
#ifdef NSBENCH_HAVE_ODE
  v.push_back("ODE " + ode_version());
#endif
  return v.empty() ? "none" : fmt::format("{}", fmt::join(v, ", "));
}

}  // namespace nsb
