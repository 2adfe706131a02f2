// The impulses every scheme reports obey Coulomb's law at every step of every friction problem:
// |Lambda_T| <= mu Lambda_N per contact (in 3D, |(Lambda_T, Lambda_T2)| <= mu Lambda_N), so no
// tangential impulse without a normal one. A scheme that left an earlier step's tangential
// impulse in place (moreau-jean's second tangent row in flight did: the sphere dropped from h0
// = 0.05 reported 0.2077 with a zero normal impulse) breaks the cone in its series.
#include <catch2/catch.hpp>
#include <cmath>
#include <map>
#include <string>

#include "integrators/registry.hpp"
#include "problems/registry.hpp"
#include "run/run.hpp"
#include "tests/integrators/every_integrator.hpp"

namespace {

// Each friction problem at settings with flights, impacts, slip and stick (the defaults but
// where a contact would never open or mu would be 0), stepped about 300 times.
struct FrictionCase {
  std::string problem;
  std::map<std::string, std::string> parameters;
  double dt, t_end;
};

const std::vector<FrictionCase> kCases = {
    {"sliding-mass", {}, 2e-3, 0.6},
    {"rolling-disk", {{"h0", "0.05"}, {"e", "0.5"}}, 2e-3, 0.6},
    {"sphere", {{"h0", "0.05"}, {"e", "0.5"}}, 2e-3, 0.6},
    {"rocking-block", {}, 2e-3, 0.6},
    {"painleve-rod", {}, 1e-3, 0.3},
    {"block-2d", {{"mu", "0.5"}, {"nx", "4"}, {"ny", "2"}}, 2e-4, 0.06},
    {"two-blocks", {{"mu", "0.5"}}, 2e-4, 0.06},
    {"block-3d", {{"mu", "0.5"}}, 2e-4, 0.06},
};

}  // namespace

TEST_CASE("every scheme's impulses stay in the Coulomb cone at every step of every friction problem",
          "[integrators][friction][friction_cone]") {
  for (const FrictionCase& fc : kCases) {
    const auto problem = nsb::make_problem(fc.problem, fc.parameters);
    const nsb::Contacts& contacts = problem->contacts();
    REQUIRE(contacts.has_friction());
    for (const auto& entry : nsb::integrator_registry()) {
      if (nsb::testing::is_engine_peer(entry.name)) continue;  // their own contact models
      auto integ = nsb::testing::init_or_decline(entry, *problem);
      if (!integ) continue;
      INFO(fc.problem << ", " << entry.name);
      double worst = 0.0, scale = 0.0;
      std::string where;
      const nsb::RunOptions options{fc.dt, fc.t_end, 1, false};
      const auto r = nsb::run(*problem, *integ, options, [&](const nsb::Integrator& it, const nsb::StepInfo&) {
        const nsb::Vec& normal = it.impulses();
        for (Eigen::Index i = 0; i < normal.size(); ++i) {
          const double t1 = it.tangential_impulses().size() > i ? it.tangential_impulses()[i] : 0.0;
          const double t2 = it.tangential_impulses2().size() > i ? it.tangential_impulses2()[i] : 0.0;
          const double excess = std::hypot(t1, t2) - contacts.mu[i] * normal[i];
          scale = std::max(scale, std::abs(normal[i]));
          if (excess > worst) {
            worst = excess;
            where = "t = " + std::to_string(it.state().t) + ", contact " + std::to_string(i) + ": Lambda_N " +
                    std::to_string(normal[i]) + ", |Lambda_T| " + std::to_string(std::hypot(t1, t2));
          }
        }
      });
      INFO("worst excess " << worst << " at " << where << "; status " << nsb::status_name(r.status));
      // Round-off of the local solves: 1e-9 of the largest normal impulse of the run.
      CHECK(worst <= 1e-9 * std::max(scale, 1e-300));
    }
  }
}
